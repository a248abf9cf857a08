"""Load a whole fitting case: its files (``unsew.io.case.read_case``) and its wearer.

The wearer is body.obj with its skeleton.json, body.obj alone (rigged from its mesh, and the
case says so: ``case.body.rigged`` and a line in ``case.notes``), or the body model meta.json
names. Then the garment is checked to lie on its wearer.
"""

from __future__ import annotations

import os

import numpy as np

from unsew.body.anny_body import make_anny_body
from unsew.body.body import Body, default_body, load_body
from unsew.errors import InputError
from unsew.io.case import Case, CaseFiles, read_case

__all__ = ["load_case", "load_case_body", "load_wearer", "check_garment_on_body", "MAX_GARMENT_GAP"]

#: The garment's median distance from its wearer's vertices above which they do not overlap [m].
#: Worn truth cases lie at 0.02 (tshirt, dress) to 0.07 (skirt); a tshirt moved 0.3 m forward
#: reads 0.22, moved 1 m sideways 0.58 (a shift within the arms' reach stays below).
MAX_GARMENT_GAP = 0.2


def load_case(
    path: str | os.PathLike,
    *,
    units: str | None = None,
    up: str | None = None,
    front: str | None = None,
    garment: str | None = None,
    truth: bool = True,
) -> Case:
    """Load and check a case folder (FORMATS.md). Options override meta.json's
    units/up/front/garment; ``truth=False`` leaves its pattern_gt.json unread. Raises InputError
    with a one-line reason on bad input."""
    files = read_case(path, units=units, up=up, front=front, garment=garment, need_truth=truth)
    body = load_case_body(files)
    target = files.files["target"]
    check_garment_on_body(files.target_verts, body, what=f"target {target}")
    return Case(
        files.path,
        files.garment,
        files.target_verts,
        files.target_faces,
        body,
        files.meta,
        files.pattern_gt,
        files.files,
        files.target_repair,
    )


def load_wearer(path: str | os.PathLike) -> Body:
    """The wearer of a case folder, its target not needed (``unsew drape --body CASE`` on a case
    made before its garment is draped). Raises InputError with a one-line reason on bad input."""
    return load_case_body(read_case(path, need_target=False, need_truth=False))


def load_case_body(files: CaseFiles) -> Body:
    """The wearer of a read case: its body mesh (rigged when it has no skeleton.json) or the
    body model its meta.json names. A skeleton.json whose body measures otherwise than the
    mesh alone says (``unsew.body.measure.cross_check_rig``) is refused in one line."""
    if files.body_mesh is not None:
        body = load_body(files.body_mesh, files.skeleton, units=files.units, up=files.up, front=files.front)
        if files.skeleton is not None:  # a skeleton of another convention must measure as the mesh does
            from unsew.body.measure import cross_check_rig

            cross_check_rig(body)
        return body
    spec = files.body_spec
    if spec == "default":
        return default_body()
    if isinstance(spec, dict) and spec.get("model") == "anny":
        return make_anny_body(phenotype=spec.get("phenotype", {}), pose=spec.get("pose", "A"))
    raise InputError(f'meta.json "body" must be "default" or {{"model": "anny", ...}}, got {spec!r}')


def check_garment_on_body(target_verts: np.ndarray, body: Body, *, what: str = "target") -> None:
    """Refuse a garment that does not lie on its wearer (another frame, units or place).

    target_verts: (V, 3) float64 [m], world frame. The garment's median distance to the body's
    vertices must be under MAX_GARMENT_GAP."""
    from scipy.spatial import cKDTree

    d, _ = cKDTree(np.asarray(body.verts)).query(np.asarray(target_verts, dtype=np.float64))
    gap = float(np.median(d))
    if gap > MAX_GARMENT_GAP:
        raise InputError(
            f"{what} does not lie on its wearer (median {gap * 100:.0f} cm from the body): give garment "
            "and body in the same frame (--up/--front/--units) and place"
        )
