"""Known-truth fitting cases made with our own simulator: a base pattern altered by known amounts
(hem, sleeve and leg lengths and widths), in a known material, draped on a body. The case folder
(FORMATS.md) holds the drape as target.obj and the altered pattern as pattern_gt.json, so a fit
can be judged against the truth. Used by the demo, the tests and the benchmarks.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from unsew.body.body import default_body, load_body
from unsew.body.measure import measure_body
from unsew.body.skeleton import save_skeleton
from unsew.dress import dress
from unsew.fit.config import FitConfig
from unsew.grading.alter import alter_pattern, alteration_groups
from unsew.io.atomic import atomic_dir
from unsew.io.garmentcode import load_pattern, save_pattern
from unsew.io.mesh import write_obj
from unsew.pattern.base import make_base_pattern
from unsew.sim.material import Material, get_material, material_to_dict

__all__ = ["Alteration", "make_truth_pattern", "make_truth_case", "DEFAULT_ALTERATIONS", "off_library"]


@dataclass(frozen=True)
class Alteration:
    """Changes from the base pattern, per group of open edges (unsew.grading.alter.alteration_groups).

    changes: group ("hem", "sleeves", "legs") -> (length [m], girth [-]): the open edges move
    outward by ``length`` and widen by the fraction ``girth``; "group@panel" (e.g. "hem@back")
    alters only that panel's edges of the group, which grading (one length and girth per
    contour) cannot express; "waist" -> (length, _): the waist corners of the side seams (where
    two side-seam edges meet, dresses) move outward by ``length`` (negative: a fitted waist),
    a shape that no open contour carries, so grading cannot make it either. material: the true fabric (library
    name). A group the garment does not have is ignored.
    """

    changes: dict = field(default_factory=dict)
    material: object = "jersey"  #: library name or a unsew.sim.material.Material

    def as_dict(self) -> dict:
        mat = material_to_dict(self.material) if isinstance(self.material, Material) else self.material
        return {
            "changes": {k: {"length_m": v[0], "girth_frac": v[1]} for k, v in self.changes.items()},
            "material": mat,
        }


def off_library(name: str, seed: int = 0):
    """A fabric that is in no library: the library material ``name`` with its stretch, shear and
    bending stiffness each scaled by a random factor exp(N(0, 0.4)) (about x0.67-x1.5 at one
    sigma; H01 keeps its Poisson ratio), density by exp(N(0, 0.15)) and friction moved by
    U(-0.05, 0.05). Seeded by ``seed`` and the name; for benchmarks whose truth must not be a
    candidate of ``material: auto``. Returns a Material (units as in unsew.sim.material)."""
    import math
    import zlib

    m = get_material(name)
    rng = np.random.default_rng([seed, zlib.crc32(name.encode())])
    f_uu, f_vv, f_s, f_b = (float(f) for f in np.exp(rng.normal(0.0, 0.4, 4)))
    h00, h11 = m.h00 * f_uu, m.h11 * f_vv
    nu = m.h01 / math.sqrt(m.h00 * m.h11)
    return Material(
        h00,
        nu * math.sqrt(h00 * h11),
        h11,
        m.h22 * f_s,
        m.bend * f_b,
        m.density * float(np.exp(rng.normal(0.0, 0.15))),
        max(0.05, m.friction + float(rng.uniform(-0.05, 0.05))),
    )


#: One alteration per garment type, used by the per-garment fit benchmark (bench_fit.py).
DEFAULT_ALTERATIONS = {
    "tshirt": Alteration({"hem": (0.06, 0.06), "sleeves": (0.03, 0.0)}, "jersey"),
    "dress": Alteration({"hem": (-0.08, 0.08), "sleeves": (0.02, 0.0)}, "silk"),
    "pants": Alteration({"legs": (-0.06, 0.08)}, "denim"),
    "shorts": Alteration({"legs": (0.05, -0.06)}, "polyester"),
    "skirt": Alteration({"hem": (0.07, 0.10)}, "wool"),
}


def make_truth_pattern(garment: str, alteration: Alteration, *, body=None):
    """The base pattern of ``garment`` sized to ``body`` (default body when None), altered."""
    body = body if body is not None else default_body()
    p = make_base_pattern(garment, measure_body(body))
    groups = alteration_groups(p)
    for key, (length, girth) in alteration.changes.items():
        if key == "waist":
            p = _move_waist(p, length)
            continue
        group, _, panel = key.partition("@")
        edges = [e for e in groups.get(group, []) if not panel or e[0] == panel]
        if edges:
            p = alter_pattern(p, edges, length=length, girth=girth)
    p.name = f"truth_{garment}"
    return p


def _move_waist(pattern, length: float):
    """A copy of ``pattern`` whose side-seam corners (a vertex between two edges labelled
    ``left_side`` or two labelled ``right_side``) move by ``length`` [m] horizontally, away from
    the panel's vertical centre line. Mirror images move alike, so stitched side seams keep
    matching lengths."""
    out = pattern.copy()
    for panel in out.panels.values():
        ends = {}
        for e in panel.edges:
            if e.label in ("left_side", "right_side"):
                ends.setdefault((e.label, e.start), 0)
                ends.setdefault((e.label, e.end), 0)
                ends[(e.label, e.start)] += 1
                ends[(e.label, e.end)] += 1
        centre = 0.5 * (panel.vertices[:, 0].min() + panel.vertices[:, 0].max())
        for (_, v), n in ends.items():
            if n == 2:
                panel.vertices[v, 0] += length * np.sign(panel.vertices[v, 0] - centre)
    return out


def make_truth_case(
    case_dir: Path,
    *,
    garment: str = "tshirt",
    alteration: Alteration | None = None,
    body=None,
    body_meta="default",
    settings=None,
    progress=None,
) -> Path:
    """Drape the true pattern and write the case folder. ``body``: a Body (default body when None);
    ``body_meta``: what meta.json says of the body ("default"), or None to write body.obj and
    skeleton.json into the case. Returns the folder.

    The target is dressed the way a fit dresses its patterns: ``settings``
    (:class:`~unsew.sim.drape.DrapeSettings`) defaults to :class:`~unsew.fit.config.FitConfig`'s
    on a 3 cm mesh (pass a fit's own when it differs), so that the true pattern in the true fabric,
    dressed like a fit, lies on its target (dress()'s shorter defaults leave a garment still
    settling). A body written into the case
    (``body_meta=None``) is written first and the target draped on it as loaded back (see below).
    """
    alteration = alteration or DEFAULT_ALTERATIONS[garment]
    body = body if body is not None else default_body()
    p = make_truth_pattern(garment, alteration, body=body)
    settings = settings if settings is not None else FitConfig().drape.replace(edge_length=0.03)
    meta = {"garment": garment, "units": "m", "up": "y", "front": "z", "truth": alteration.as_dict()}
    with atomic_dir(case_dir, overwrite=True) as tmp:
        if body_meta is None:
            # The target is draped on the body exactly as a fit will load it from the case: an
            # OBJ and skeleton.json carry no skinning weights, and the panel placement reads body
            # parts from the weights when present (Body.vertex_parts). Draped on the in-memory
            # body, benchmark case tshirt_02's true pattern in its true fabric lay 5.38 mm from
            # its target as the fit sees it; the gap was the placement, not the physics.
            write_obj(tmp / "body.obj", body.verts, body.faces)
            save_skeleton(body.skeleton, tmp / "skeleton.json")
            body = load_body(tmp / "body.obj", tmp / "skeleton.json")
        else:
            meta["body"] = body_meta
        # Likewise the pattern: draped as pattern_gt.json reads back (its rounding can move a
        # mesh vertex), so the true pattern reproduces the target exactly.
        save_pattern(p, tmp / "pattern_gt.json")
        p = load_pattern(tmp / "pattern_gt.json")
        d = dress(p, body, material=alteration.material, settings=settings, progress=progress)
        write_obj(
            tmp / "target.obj", np.asarray(d.x), d.mesh.faces, header=f"unsew known-truth target ({garment})"
        )
        (tmp / "meta.json").write_text(json.dumps(meta, indent=2))
    return Path(case_dir)
