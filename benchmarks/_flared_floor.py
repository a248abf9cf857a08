"""Where does unsew's drape of a true pattern part from the newton target on flared skirts?

For each foreign case (benchmarks/foreign/cases/ID), unsew dresses the case's true pattern on
its body as ``unsew drape CASE/pattern_gt.json --body CASE`` does (the library's cotton, the
default DRESS_SETTINGS), or with ``--fabric newton`` the newton targets' own fabric
(``bench_fabric_tests.newton_target_fabric``: density, membrane and the plate rigidity its
Style3D bending stands for). Printed per case: the floor (Chamfer to target.obj [mm], 50k
samples, as ``benchmarks/foreign/run.py floor`` measures it) and the shape of both drapes: the
garment's top and bottom heights [m], the hem's mean radius about the target's vertical axis [m]
(vertices within 3 cm of the bottom), and the mean distance from the target's vertices to the
drape [mm] in 10 cm height bands from the hem up.

With ``--newton-again FRAMES`` the drape compared is newton's own, run again from today's
placement (the targets' simulator against itself: how far its result moves with its sewing
settings and the settle time).

With ``--against DIR`` the drape is compared with DIR/CASE.obj (another drape that ``--out``
wrote, e.g. newton's settled longer) instead of the case's target.

Run: python -m benchmarks fabric_tests --flared-floor [--cases ID ...] [--fabric cotton|newton] [--out DIR]
     [--newton-again FRAMES] [--against DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
CASES = HERE / "foreign" / "cases"
#: the flared and circle drafts, and three others that must not get worse
DEFAULT_CASES = (
    "skirt_circle_knee__default",
    "skirt_circle_knee__gc_mean_all_tpose",
    "skirt_circle_mini__default",
    "skirt_flared_midi__default",
    "skirt_flared_midi__gc_mean_female",
    "skirt_flared_midi__tall_thin",
    "skirt_flared_midi__male_heavy",
    "skirt_flared_knee__older",
    "tee_fitted_short__default",
    "trousers_straight__default",
    "dress_shift_sleeved__default",
)


def read_obj(path: Path):
    """Vertices (V, 3) [m] and triangles (F, 3) of an OBJ (the first three corners of a face)."""
    v, f = [], []
    for ln in Path(path).read_text().splitlines():
        if ln.startswith("v "):
            v.append([float(t) for t in ln.split()[1:4]])
        elif ln.startswith("f "):
            f.append([int(t.split("/")[0]) - 1 for t in ln.split()[1:4]])
    return np.asarray(v), np.asarray(f, dtype=np.int64)


def shape(x: np.ndarray, axis: np.ndarray) -> dict:
    """Top and bottom heights [m] of vertices x (V, 3) and the hem's mean radius [m] about the
    vertical line through ``axis`` (x, z) (vertices within 3 cm of the bottom)."""
    y = x[:, 1]
    low = y < y.min() + 0.03
    r = np.hypot(x[low, 0] - axis[0], x[low, 2] - axis[1])
    return {"top": float(y.max()), "bottom": float(y.min()), "hem_r": float(r.mean())}


def band_distances(x: np.ndarray, target: np.ndarray, *, band: float = 0.1) -> list[float]:
    """Mean distance [mm] from the target's vertices (T, 3) to the nearest drape vertex x (V, 3),
    per height band of ``band`` [m] from the target's bottom up."""
    from scipy.spatial import cKDTree

    d = cKDTree(x).query(target)[0]
    y = target[:, 1]
    edges = np.arange(y.min(), y.max() + 1e-9, band)
    sel = [(y >= lo) & (y < lo + band) for lo in edges]
    return [float(1000 * d[m].mean()) for m in sel if m.any()]


def drape_case(case: Path, fabric: str, changes: dict | None = None):
    """unsew's drape of the case's true pattern: (x (n, 3) [m], faces (F, 3)). ``changes``: the
    material's fields (``m.NAME``, e.g. ``m.h22``) and DRESS_SETTINGS' fields to set, or None."""

    from unsew.commands._checks import check_pattern_scale
    from unsew.dress import DRESS_SETTINGS, dress
    from unsew.io.garmentcode import load_pattern
    from unsew.sim.material import Material, get_material

    pattern = load_pattern(case / "pattern_gt.json")
    body = _body(case)
    check_pattern_scale(pattern, body)
    if fabric == "newton":
        import bench_fabric_tests as ft

        fab = ft.newton_target_fabric()
        h = fab.membrane
        mat = Material(h[0], h[1], h[2], h[3], fab.bend, fab.density, friction=0.5)
    else:
        mat = get_material(fabric)
    changes = dict(changes or {})
    mat = dataclasses.replace(mat, **{k[2:]: float(v) for k, v in changes.items() if k.startswith("m.")})
    settings = DRESS_SETTINGS.replace(
        **{k: type(getattr(DRESS_SETTINGS, k))(v) for k, v in changes.items() if not k.startswith("m.")}
    )
    d = dress(pattern, body, material=mat, settings=settings)
    return d.x.detach().cpu().numpy(), np.asarray(d.mesh.faces)


def newton_again(case: Path, settle_frames: int, changes: dict | None = None):
    """newton's drape of the case's true pattern run again from today's placement, with
    newton_drape's first fallback (seam force and speed capped while sewing), ``settle_frames``
    and ``changes`` to newton_drape.SETTINGS (numbers): (x (n, 3) [m], faces (F, 3))."""
    import json
    import warnings

    sys.path.insert(0, str(HERE / "foreign"))
    import newton_drape

    from unsew.body.placement import place_garment
    from unsew.io.garmentcode import pattern_from_dict
    from unsew.meshing.sew import mesh_pattern

    body = _body(case)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pattern = pattern_from_dict(json.loads((case / "pattern_gt.json").read_text()), name=case.name)
    mesh = mesh_pattern(pattern, edge_length=0.025)
    x0 = place_garment(pattern, mesh, body)
    s = {**newton_drape.SETTINGS, **newton_drape.FALLBACKS[1], "settle_frames": settle_frames}
    s.update({k: type(s[k])(float(v)) for k, v in (changes or {}).items()})
    lower = case.name.startswith(("skirt", "trousers", "shorts"))
    x, _ = newton_drape.drape_newton(
        mesh, x0, body.verts, body.faces, lower=lower, settings=s, log=lambda m: None
    )
    return x, np.asarray(mesh.faces)


def _body(case: Path):
    from unsew.commands.drape import _load_body

    return _load_body(argparse.Namespace(body=str(case), skeleton=None, units="m"))


def run_case(case: Path, fabric: str, out: Path | None, newton_frames=0, changes=None, against=None) -> dict:
    """One row: the floor [mm], both drapes' shapes and the band distances (``newton_frames`` > 0:
    newton's own drape run again (:func:`newton_again`) in place of unsew's; ``against``: a folder
    whose CASE.obj stands in for the target)."""
    from unsew.metrics.surface import chamfer_mm

    t0 = time.time()
    x, f = newton_again(case, newton_frames, changes) if newton_frames else drape_case(case, fabric, changes)
    tv, tf = read_obj(against / f"{case.name}.obj" if against is not None else case / "target.obj")
    c = chamfer_mm(x, f, tv, tf, n_samples=50_000)
    axis = tv[:, [0, 2]].mean(0)
    ours, theirs = shape(x, axis), shape(tv, axis)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        from unsew.io.mesh import write_obj

        write_obj(out / f"{case.name}.obj", x, f)
    return {
        "case": case.name,
        "drape": f"newton again, {newton_frames} settle frames"
        + "".join(f", {k}={v}" for k, v in (changes or {}).items())
        if newton_frames
        else f"unsew, {fabric}" + "".join(f", {k}={v}" for k, v in (changes or {}).items()),
        "floor mm": round(c.mean_mm, 2),
        "top m (target)": f"{ours['top']:.3f} ({theirs['top']:.3f})",
        "bottom m (target)": f"{ours['bottom']:.3f} ({theirs['bottom']:.3f})",
        "hem radius m (target)": f"{ours['hem_r']:.3f} ({theirs['hem_r']:.3f})",
        "target to drape by 10 cm band from the hem, mm": " ".join(f"{v:.0f}" for v in band_distances(x, tv)),
        "s": round(time.time() - t0, 1),
    }


def _changes(args) -> dict | None:
    """``--set``'s KEY=VALUE pairs as a dict, checked against the material's fields and
    DRESS_SETTINGS (or newton_drape.SETTINGS with ``--newton-again``); None (and one line on
    stderr) when one names nothing."""
    try:
        changes = dict(kv.split("=", 1) for kv in args.set)
    except ValueError:
        print("flared_floor: --set takes KEY=VALUE", file=sys.stderr)
        return None
    from unsew.dress import DRESS_SETTINGS
    from unsew.sim.material import Material

    fields = {f.name for f in dataclasses.fields(Material)}
    if args.newton_again:
        sys.path.insert(0, str(HERE / "foreign"))
        from newton_drape import SETTINGS

        bad = [k for k in changes if k not in SETTINGS]
    else:
        bad = [
            k for k in changes if not (k[2:] in fields if k.startswith("m.") else hasattr(DRESS_SETTINGS, k))
        ]
    if bad:
        print(f"flared_floor: --set {bad[0]!r} is neither m.<material field> nor a setting", file=sys.stderr)
        return None
    return changes


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m benchmarks fabric_tests --flared-floor", description=__doc__.splitlines()[0]
    )
    ap.add_argument("--cases", nargs="+", default=list(DEFAULT_CASES))
    ap.add_argument("--fabric", default="cotton", help="a library material, or newton (the targets' fabric)")
    ap.add_argument("--out", type=Path, default=None, help="write each drape as DIR/CASE.obj")
    ap.add_argument(
        "--against",
        type=Path,
        default=None,
        help="compare with DIR/CASE.obj (another drape written by --out) instead of the case's target",
    )
    ap.add_argument(
        "--newton-again",
        type=int,
        default=0,
        metavar="FRAMES",
        help="instead of unsew's drape, newton's own run again with FRAMES settle frames (minutes a case)",
    )
    ap.add_argument(
        "--set",
        nargs="+",
        default=[],
        metavar="KEY=VALUE",
        help="change the material (m.h22=600, m.bend=2e-5, m.friction=0.1) or a DRESS_SETTINGS field "
        "(settle_steps=80, spring_stiffness=100); with --newton-again, newton_drape.SETTINGS (iterations=30)",
    )
    args = ap.parse_args(argv)
    changes = _changes(args)
    if changes is None:
        return 2
    missing = [c for c in args.cases if not (CASES / c / "target.obj").is_file()]
    if missing:
        print(f"flared_floor: no case {missing[0]!r} in {CASES}", file=sys.stderr)
        return 2
    absent = [c for c in args.cases if args.against and not (args.against / f"{c}.obj").is_file()]
    if absent:
        print(f"flared_floor: --against {args.against} has no {absent[0]}.obj", file=sys.stderr)
        return 2

    import torch

    torch.set_num_threads(1)
    from tables import markdown_table

    rows = []
    for c in args.cases:
        rows.append(run_case(CASES / c, args.fabric, args.out, args.newton_again, changes, args.against))
        print(" ".join(f"{k}: {v}" for k, v in rows[-1].items()), flush=True)
    print()
    print(markdown_table(rows, digits=2))
    fl = [r["floor mm"] for r in rows if r["case"].startswith(("skirt_circle", "skirt_flared"))]
    if fl:
        print(f"\nflared and circle floors: median {np.median(fl):.2f} mm over {len(fl)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
