"""Generate the benchmark's other wearers once, with anny: benchmarks/data/*.npz.

Three bodies besides the embedded default one (anny, all phenotypes 0.5, A-pose):

- ``tall_heavy``: taller, heavier, more muscular (gender 0.8: male side of anny's scale);
- ``small_slim``: shorter and slimmer (gender 0.2, weight 0.3);
- ``pose_step``: the default phenotype in another pose, the left arm raised 0.3 rad and the
  right leg stepped 0.2 rad forward (rotations in the world frame, applied to each subtree).

Stored like src/unsew/data/default_body.npz (float32 vertices, top-4 skinning weights), so the
benchmark reruns without anny. Run with a Python that has anny installed (never uses anny's
non-commercial download):

    ANNY_CACHE_DIR=/tmp/anny_cache OMP_WAIT_POLICY=PASSIVE PYTHONPATH=src \
        /tmp/venvtest/bin/python benchmarks/make_bodies.py
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "src"))  # works without installing unsew

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

#: name -> (phenotype overrides, pose). Missing phenotypes are 0.5.
BODIES = {
    "tall_heavy": ({"gender": 0.8, "height": 0.75, "weight": 0.7, "muscle": 0.65}, "A"),
    "small_slim": ({"gender": 0.2, "height": 0.3, "weight": 0.3}, "A"),
    "pose_step": ({}, {"left_shoulder": [0.0, 0.0, 0.3], "right_hip": [-0.2, 0.0, 0.0]}),
}


def main() -> None:
    import anny
    import torch

    torch.set_num_threads(1)
    from unsew.body.anny_body import PHENOTYPES, make_anny_body, save_body_npz

    out_dir = os.path.join(HERE, "data")
    os.makedirs(out_dir, exist_ok=True)
    for name, (ph, pose) in BODIES.items():
        full = {k: ph.get(k, 0.5) for k in PHENOTYPES}
        body = make_anny_body(full, pose=pose, top_k=4)
        out = os.path.join(out_dir, f"body_{name}.npz")
        meta = {
            "source": f"anny {getattr(anny, '__version__', '?')} (Apache-2.0 code, CC0 data)",
            "phenotype": full,
            "pose": pose,
            "frame": "metres, Y up, facing +Z, left at +X; soles at y=0; pelvis joint at x=z=0",
            "generator": "benchmarks/make_bodies.py",
        }
        save_body_npz(body, out, top_k=4, meta=meta)
        print(
            f"{out}: {len(body.verts)} verts, height {body.height:.3f} m, {os.path.getsize(out) / 1e3:.0f} KB"
        )


if __name__ == "__main__":
    main()
