"""Does the wrapped start give every panel of designs made elsewhere the role its name says?

`unsew.body.placement.panel_roles` reads each panel's role (sleeve, leg, torso, free) from its own
3D placement against the body's skeleton, never from its name. Here the names of GarmentCode's
specifications say which panels are arm pieces (a name with ``sleeve`` or ``cuff``, not
``pant``), and the roles are checked against them, on: the GarmentCode sample's true patterns
(their bodies, as ``gcd build`` writes them), GarmentCode's four sample patterns (mean_all), the
foreign benchmark's drafts (their bodies) and, with ``--seeds``, more designs of GarmentCode's
sampler on the sample's five bodies. For the panels out by an arm it prints how near the centre
plane the arm pieces and the other panels come (their nearest corner over the shoulder's offset,
docs/decisions/053), and every panel whose role and name disagree.

    python -m benchmarks panel_roles [--seeds 101-105 --count 16] [--out DIR]
    python -m benchmarks panel_roles --small    # GarmentCode's four sample patterns only
    python -m benchmarks panel_roles --designs  # unsew's own design space, drafted on three bodies
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
GCD_CASES = HERE / "gcd" / "cases"
FOREIGN_CASES = HERE / "foreign" / "cases"
#: the five bodies of the GarmentCode sample, by seed (benchmarks/gcd/manifest.json), as built
BODIES = GCD_CASES / "_bodies"


def _shared() -> Path:
    import os

    return Path(os.environ.get("UNSEW_SHARED", ROOT.parent / "shared"))


def is_arm_piece(name: str) -> bool:
    """Whether a GarmentCode panel name names a piece of a sleeve (a sleeve half, a cuff)."""
    return ("sleeve" in name or "cuff" in name) and "pant" not in name


def panel_rows(spec: Path, body, tag: str) -> list[dict]:
    """One row per panel of the specification ``spec`` on ``body``: tag, panel, its name's part
    (``arm`` or ``other``), its role, whether it lies out by an arm (centre above the crotch,
    beyond 0.8 of the shoulder's offset, near the arm's bones; not a collar or hood, which are
    placed by their height before any sleeve) and its nearest corner's share of
    the shoulder's offset from the centre plane [-]. A specification unsew refuses gives none."""
    from unsew.body.placement import SLEEVE_REACH, _arm_distance, _landmarks, panel_roles
    from unsew.errors import UnsewError
    from unsew.io.garmentcode import load_pattern

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            pattern = load_pattern(spec)
    except UnsewError:
        return []
    roles = panel_roles(pattern, body)
    J, _, _, cx, crotch_y = _landmarks(body)
    rows = []
    for name in pattern.panel_order:
        p = pattern.panels[name]
        w = p.to_world(p.vertices)
        c = w.mean(axis=0)
        side = "left" if c[0] > cx else "right"
        off = abs(J[f"{side}_shoulder"][0] - cx)
        out = (
            c[1] > crotch_y + 0.1 and abs(c[0] - cx) > 0.8 * off and _arm_distance(c, J, side) < SLEEVE_REACH
        )
        out = out and roles[name] != "free"  # a collar or hood is placed by its height first
        rows.append(
            dict(
                tag=tag,
                panel=name,
                part="arm" if is_arm_piece(name) else "other",
                role=roles[name],
                out_by_arm=bool(out),
                inner=float(np.min(np.abs(w[:, 0] - cx)) / max(off, 1e-6)),
            )
        )
    return rows


def _load(mesh: Path, skeleton: Path | None):
    from unsew.body.body import load_body

    return load_body(mesh, skeleton if skeleton is not None and skeleton.is_file() else None)


def gather(*, small: bool, seeds=(), count: int = 16, out: Path | None = None) -> tuple[list[dict], int]:
    """(the panel rows of every specification found, the number of specifications)."""
    specs = []
    shared = _shared()
    mean_all = shared / "foreign" / "bodies" / "mean_all.obj"
    if mean_all.is_file():
        body = _load(mean_all, None)
        specs += [(p, body, p.stem) for p in sorted((shared / "foreign" / "patterns").glob("*.json"))]
    if not small:
        for d in sorted(GCD_CASES.glob("gc_*")):
            if (d / "pattern_gt.json").is_file():
                specs.append((d / "pattern_gt.json", (d / "body.obj", d / "skeleton.json"), d.name))
        if FOREIGN_CASES.is_dir():
            from unsew.body.case import load_case_body
            from unsew.io.case import read_case

            bodies = {}
            for d in sorted(p for p in FOREIGN_CASES.iterdir() if (p / "pattern_gt.json").is_file()):
                key = json.dumps(json.loads((d / "meta.json").read_text())["body"], sort_keys=True)
                if key not in bodies:
                    bodies[key] = load_case_body(read_case(d))
                specs.append((d / "pattern_gt.json", bodies[key], d.name))
        specs += _sampled(seeds, count, out)
    rows, loaded = [], {}
    for spec, body, tag in specs:
        if isinstance(body, tuple):
            if body not in loaded:
                loaded[body] = _load(*body)
            body = loaded[body]
        rows += panel_rows(spec, body, tag)
    return rows, len(specs)


def _sampled(seeds, count: int, out: Path | None) -> list:
    """GarmentCode's sampler run for each of ``seeds`` (``count`` designs) on the sample's body of
    the same seed modulo 5, as ``gcd build`` sizes them: (spec, (body.obj, skeleton.json), tag)."""
    if not seeds:
        return []
    sys.path.insert(0, str(HERE))
    from gcd.build import manifest, sample_seed

    names = {s["seed"]: s["body"]["name"] for s in manifest()["seeds"]}
    root = Path(out) if out else Path(tempfile.mkdtemp(prefix="panel_roles_"))
    specs = []
    for seed in seeds:
        body_dir = BODIES / names[(seed - 1) % 5 + 1]
        if not (body_dir / "body.yaml").is_file():
            raise SystemExit(
                f"panel_roles: no {body_dir}/body.yaml; run python -m benchmarks gcd build --no-drape"
            )
        d = sample_seed(seed, count, body_dir, root)
        for spec in sorted(d.glob("*/*_specification.json")):
            specs.append((spec, (body_dir / "body.obj", body_dir / "skeleton.json"), spec.stem))
    return specs


def summary(rows: list[dict], n_specs: int) -> tuple[str, list[dict]]:
    """(a table of the panels out by an arm, arm pieces against the others; the rows whose role
    and name disagree)."""
    from tables import markdown_table

    bad = [r for r in rows if (r["part"] == "arm") != r["role"].endswith("_sleeve")]
    out = [r for r in rows if r["out_by_arm"]]
    table = []
    for part in ("arm", "other"):
        share = np.array([r["inner"] for r in out if r["part"] == part])
        table.append(
            {
                "panels out by an arm": part,
                "count": len(share),
                "nearest corner min": f"{share.min():.3f}" if len(share) else "",
                "nearest corner max": f"{share.max():.3f}" if len(share) else "",
            }
        )
    text = f"{n_specs} specifications, {len(rows)} panels\n\n" + markdown_table(table, list(table[0]))
    return text, bad


def design_rows(every: int = 3) -> tuple[list[dict], int]:
    """Panel rows (:func:`panel_rows`' keys) of every ``every``-th design of unsew's design space
    (``unsew.pattern.design.design_space`` of each garment) drafted on three of the sample's bodies
    (GarmentCode's mean female and T-pose mean, the short anny body), and the number of patterns."""
    from unsew.body.measure import measure_body
    from unsew.body.placement import panel_roles
    from unsew.errors import InputError
    from unsew.pattern.design import GARMENTS, design_name, design_space, draft

    rows, n = [], 0
    for name in ("gc_mean_female", "gc_mean_all_tpose", "anny_height_0.2_apose"):
        if not (BODIES / name / "body.obj").is_file():
            raise SystemExit(
                f"panel_roles: no {BODIES / name}; run python -m benchmarks gcd build --no-drape"
            )
        body = _load(BODIES / name / "body.obj", BODIES / name / "skeleton.json")
        m = measure_body(body)
        for garment in GARMENTS:
            for d in design_space(garment)[::every]:
                try:
                    pattern = draft(d, m)
                except InputError:
                    continue
                n += 1
                roles = panel_roles(pattern, body)
                tag = f"{name}/{design_name(d)}"
                rows += [
                    dict(
                        tag=tag,
                        panel=p,
                        part="arm" if is_arm_piece(p) else "other",
                        role=r,
                        out_by_arm=False,
                        inner=0.0,
                    )
                    for p, r in roles.items()
                ]
    return rows, n


def _seeds(text: str | None) -> list[int]:
    if not text:
        return []
    a, _, b = text.partition("-")
    return list(range(int(a), int(b or a) + 1))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--small", action="store_true", help="GarmentCode's four sample patterns only")
    ap.add_argument("--seeds", help="also this range of GarmentCode sampler seeds, e.g. 101-105")
    ap.add_argument("--count", type=int, default=16, help="designs per sampled seed (default 16)")
    ap.add_argument("--out", help="folder for the sampled designs (default: a temporary one)")
    ap.add_argument(
        "--designs",
        action="store_true",
        help="unsew's own design space instead (every third design, three bodies)",
    )
    args = ap.parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's gathered seams: stitched lengths apart
        if args.designs:
            rows, n = design_rows()
        else:
            rows, n = gather(small=args.small, seeds=_seeds(args.seeds), count=args.count, out=args.out)
    if not rows:
        print(
            "panel_roles: no specifications found (GarmentCode's patterns, benchmarks/gcd/cases)",
            file=sys.stderr,
        )
        return 2
    text, bad = summary(rows, n)
    print(text)
    print(f"\n{len(bad)} panels whose role and name disagree")
    for r in bad:
        print(
            f"  {r['tag']}: {r['panel']} ({r['part']}) placed as {r['role']}, nearest corner {r['inner']:.3f}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
