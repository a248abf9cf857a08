"""``unsew pattern symmetry P.json [--json]``: panels, inter-panel pairs, mirror axes, and the
number of all control points and of the effective ones K (Algorithm 1)."""

from __future__ import annotations

import argparse
import json

__all__ = ["run", "symmetry_report"]


def symmetry_report(pattern) -> dict:
    """Plain-JSON summary of a pattern's control points and symmetry (lengths in metres)."""
    from unsew.pattern.controls import find_control_points
    from unsew.pattern.symmetry import detect_symmetry

    controls = find_control_points(pattern)
    sym = detect_symmetry(pattern, controls=controls)
    in_k = set(sym.k_indices.tolist())
    per_panel = []
    for p, name in enumerate(controls.panel_names):
        idx = controls.of_panel(p).tolist()
        per_panel.append({"name": name, "control_points": len(idx), "in_K": sum(g in in_k for g in idx)})
    return {
        "units": "m",
        "panels": per_panel,
        "pairs": [
            {
                "source": pr.source,
                "target": pr.target,
                "mirrored": bool(pr.mirrored),
                "error": round(pr.error, 6),
            }
            for pr in sym.pairs
        ],
        "mirror_axes": [
            {
                "panel": m.panel,
                "point": [round(float(x), 6) + 0.0 for x in m.point],
                "direction": [round(float(x), 6) + 0.0 for x in m.direction],
                "on_axis": len(m.on_axis),
                "mirrored_points": len(m.pairs),
                "error": round(m.error, 6),
            }
            for m in sym.mirrors
        ],
        "control_points": sym.n_control,
        "K": sym.n_k,
    }


def run(args: argparse.Namespace) -> int:
    from unsew.io.garmentcode import load_pattern

    rep = symmetry_report(load_pattern(args.pattern))
    if args.json:
        print(json.dumps(rep, indent=2))
        return 0
    print(f"{'panel':<20} {'control pts':>11} {'in K':>5}")
    for p in rep["panels"]:
        print(f"{p['name']:<20} {p['control_points']:>11} {p['in_K']:>5}")
    print()
    if rep["pairs"]:
        for pr in rep["pairs"]:
            kind = "mirror image" if pr["mirrored"] else "rotated copy"
            print(f"pair         {pr['target']} = {kind} of {pr['source']} (error {pr['error']:.2g})")
    else:
        print("pair         none")
    if rep["mirror_axes"]:
        for m in rep["mirror_axes"]:
            (px, py), (dx, dy) = m["point"], m["direction"]
            print(
                f"mirror axis  {m['panel']}: through ({px:.4f}, {py:.4f}) m along ({dx:.3f}, {dy:.3f}), "
                f"{m['on_axis']} point(s) on it (error {m['error']:.2g})"
            )
    else:
        print("mirror axis  none")
    print(f"\ncontrol points {rep['control_points']}, effective K {rep['K']}")
    return 0
