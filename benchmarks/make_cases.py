"""Write the benchmark's known-truth fitting cases: one case folder (FORMATS.md) per design.

For each garment type (tshirt, dress, pants, shorts, skirt) ``--per-type`` cases (default 4),
seeded and reproducible. Each case is our base pattern for that garment, sized to its wearer,
with a random design: the open edges (hem, cuffs, leg openings) moved by a random length and
widened by a random girth fraction (unsew.fit.synthetic.Alteration; on skirts and dresses the
hem girth is the flare, on tops the sleeve length and width are the sleeve shape, on pants and
shorts the leg length and opening are the leg shape: the base generators expose no other
design parameters). The material is drawn from the library, never the fit's starting cotton.
The wearer cycles through four bodies, so every garment type meets each one:

- ``default``: the embedded default body (meta.json names it; no body files written);
- ``tall_heavy``, ``small_slim``: two other anny bodies; ``pose_step``: the default
  phenotype with the left arm raised and the right leg stepped forward. These three are stored
  in benchmarks/data/ (made once by benchmarks/make_bodies.py with anny) and written into the
  case as body.obj + skeleton.json.

The drape of the true pattern by our simulator is target.obj; the true pattern is
pattern_gt.json; meta.json records the design ("truth") and the body. An existing case folder
is kept (delete it to remake it).

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/make_cases.py [--out bench-out/paper/cases]
        [--per-type 4] [--garments tshirt dress ...] [--seed 0] [--edge-length 0.025]
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
DATA = HERE / "data"

GARMENTS = ["tshirt", "dress", "pants", "shorts", "skirt"]
#: Wearers, in the order the cases of every garment cycle through them.
BODIES = ["default", "tall_heavy", "small_slim", "pose_step"]
#: Library materials a case may be made of (the fit starts from cotton).
CASE_MATERIALS = ["jersey", "silk", "denim", "polyester", "wool"]

#: garment -> {group: ((length_lo, length_hi) [m], (girth_lo, girth_hi) [-])}: uniform ranges of
#: the random design. Pants are only shortened (their base legs reach the ankle).
DESIGN_RANGES = {
    "tshirt": {"hem": ((-0.04, 0.08), (-0.04, 0.10)), "sleeves": ((-0.02, 0.06), (-0.05, 0.10))},
    "dress": {"hem": ((-0.15, 0.04), (-0.05, 0.12)), "sleeves": ((-0.01, 0.04), (-0.05, 0.08))},
    "pants": {"legs": ((-0.12, -0.01), (-0.06, 0.10))},
    "shorts": {"legs": ((-0.03, 0.08), (-0.08, 0.08))},
    "skirt": {"hem": ((-0.08, 0.10), (-0.05, 0.15))},
}


def body_by_name(name: str):
    """The wearer ``name`` (one of BODIES) as a unsew Body."""
    from unsew.body.body import body_from_npz, default_body

    if name == "default":
        return default_body()
    path = DATA / f"body_{name}.npz"
    if not path.is_file():
        raise SystemExit(
            f"{path} is missing: run benchmarks/make_bodies.py (needs anny) or restore it from git"
        )
    return body_from_npz(path)


def design(garment: str, index: int, seed: int = 0):
    """The seeded random design of case ``index`` of ``garment``: (Alteration, body name)."""
    from unsew.fit.synthetic import Alteration

    # one generator per (seed, garment, index): adding cases or garments never changes the others
    rng = np.random.default_rng([seed, GARMENTS.index(garment), index])
    changes = {}
    for group, ((l0, l1), (g0, g1)) in DESIGN_RANGES[garment].items():
        changes[group] = (round(float(rng.uniform(l0, l1)), 4), round(float(rng.uniform(g0, g1)), 4))
    material = CASE_MATERIALS[int(rng.integers(len(CASE_MATERIALS)))]
    body = BODIES[(index + GARMENTS.index(garment)) % len(BODIES)]
    return Alteration(changes, material), body


def _git_version() -> str:
    import subprocess

    try:
        return (
            subprocess.run(
                ["git", "rev-parse", "--short", "HEAD"],
                cwd=HERE.parent,
                capture_output=True,
                text=True,
                timeout=10,
            ).stdout.strip()
            or "?"
        )
    except (OSError, subprocess.SubprocessError):
        return "?"


def case_name(garment: str, index: int) -> str:
    return f"{garment}_{index:02d}"


def make_case(
    out: Path, garment: str, index: int, *, seed: int = 0, edge_length: float = 0.025, settings=None
) -> Path:
    """Write (or keep, if present) case ``index`` of ``garment`` under ``out``. Returns its folder.
    ``settings``: DrapeSettings of the target's drape (default: FitConfig's, as the fits dress),
    its edge length replaced by ``edge_length``."""
    from unsew.fit.config import FitConfig
    from unsew.fit.synthetic import make_truth_case

    d = Path(out) / case_name(garment, index)
    if (d / "meta.json").is_file():
        return d
    alt, bname = design(garment, index, seed)
    body = body_by_name(bname)
    make_truth_case(
        d,
        garment=garment,
        alteration=alt,
        body=None if bname == "default" else body,
        body_meta="default" if bname == "default" else None,
        settings=(settings or FitConfig().drape).replace(edge_length=edge_length),
    )
    meta = json.loads((d / "meta.json").read_text())
    meta["benchmark"] = {
        "body_name": bname,
        "seed": seed,
        "index": index,
        "edge_length_m": edge_length,
        "generator": "benchmarks/make_cases.py",
        "unsew_commit": _git_version(),
    }
    (d / "meta.json").write_text(json.dumps(meta, indent=2))
    return d


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="bench-out/paper/cases")
    ap.add_argument("--garments", nargs="+", default=GARMENTS, choices=GARMENTS)
    ap.add_argument("--per-type", type=int, default=4)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--edge-length", type=float, default=0.025, help="mesh of the target drape [m]")
    args = ap.parse_args(argv)

    import torch

    torch.set_num_threads(1)
    for g in args.garments:
        for i in range(args.per_type):
            t = time.perf_counter()
            d = make_case(Path(args.out), g, i, seed=args.seed, edge_length=args.edge_length)
            meta = json.loads((d / "meta.json").read_text())
            nv = sum(1 for line in open(d / "target.obj") if line.startswith("v "))
            print(
                f"{d}: {meta['benchmark']['body_name']:>10} {meta['truth']['material']:>9} "
                f"{json.dumps(meta['truth']['changes'])}  {nv} verts  {time.perf_counter() - t:.0f} s",
                flush=True,
            )


if __name__ == "__main__":
    main()
