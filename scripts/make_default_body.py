"""Generate src/unsew/data/default_body.npz: the embedded default wearer.

anny 0.6.2, all six phenotypes at 0.5, rest A-pose, converted to unsew's world frame (metres,
Y up, facing +Z, left at +X; feet at y = 0, pelvis at x = z = 0), largest closed component,
our skeleton joints and top-4 skinning weights. See unsew.body.anny_body and unsew.body.body.

Run with a Python that has anny installed (never uses anny's non-commercial download):

    ANNY_CACHE_DIR=/tmp/anny_cache OMP_WAIT_POLICY=PASSIVE python scripts/make_default_body.py

The first anny construction takes about 2 minutes and writes a ~0.8 GB cache in ANNY_CACHE_DIR.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "src"))  # works without installing unsew

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    import anny
    import torch

    torch.set_num_threads(1)
    from unsew.body.anny_body import PHENOTYPES, make_anny_body, save_body_npz

    body = make_anny_body({k: 0.5 for k in PHENOTYPES}, pose="A", top_k=4)
    out = os.path.join(HERE, "..", "src", "unsew", "data", "default_body.npz")
    meta = {
        "source": f"anny {getattr(anny, '__version__', '?')} (Apache-2.0 code, CC0 data)",
        "phenotype": {k: 0.5 for k in PHENOTYPES},
        "pose": "A",
        "frame": "metres, Y up, facing +Z, left at +X; soles at y=0; pelvis joint at x=z=0",
        "generator": "scripts/make_default_body.py",
    }
    save_body_npz(body, out, top_k=4, meta=meta)
    print(f"{out}: {len(body.verts)} verts, {len(body.faces)} faces, height {body.height:.3f} m, "
          f"{len(body.skeleton.names)} joints, {os.path.getsize(out) / 1e6:.2f} MB")


if __name__ == "__main__":
    main()
