"""Where the fit's drapes meet the body (``contact``): as unsew drapes by default, or at the gap the
target's own cloth keeps from the body.

Every simulator rests cloth at its own distance from the body: one with particles at its particle
radius, unsew where the repulsion of :mod:`unsew.sim.energies.contact` balances what the cloth
presses with, as near as the collision thickness where it is pulled tight. A band pulled round a
waist s nearer the body is a loop 2 pi s shorter, which phase two then makes up by lengthening the
pattern. With :data:`CONTACT` "target" the fit reads the gap from the target and body it is given and
drapes with a contact that rests the cloth there: the threshold at the gap, the stiffness
CONTACT_STIFF, under which a cloth pressing with p sinks s = sqrt(p / kc) into the zone (1 kPa, a
band's pressure: 1 mm). Not the default: docs/decisions/012.
"""

from __future__ import annotations

import numpy as np
import torch

from unsew.geometry.distance import point_mesh_distance

__all__ = [
    "CONTACT",
    "CONTACT_MODES",
    "CONTACT_STIFF",
    "GAP_PERCENTILE",
    "GAP_RANGE_M",
    "signed_body_distance",
    "target_gap",
    "contact_for_target",
]

#: What the fit can do with the body contact: drape.contact_stiffness below drape.contact_threshold
#: ("default"), or the threshold at the target's gap to the body, a stiffer contact ("target").
CONTACT_MODES = ("default", "target")
#: What the fit does with the body contact (docs/decisions/012: "target" measured, not adopted).
CONTACT = "default"

#: Contact stiffness kc [N/m^4] under ``contact: target`` (the default's 1e7 x 100).
CONTACT_STIFF = 1e9

#: Percentile of the target vertices' signed distances to the body read as the cloth's gap [-]:
#: the cloth pressed on the body, a few hundred vertices on a benchmark target, where the lowest
#: one would be a single vertex's noise.
GAP_PERCENTILE = 1.0

#: The gap is clamped to this range [m]: at least twice the collision thickness (a target lying on
#: or through the body, a scan's noise, gets a thin contact zone), at most 1 cm (a target that
#: nowhere comes nearer is loose all over and its contact hardly matters).
GAP_RANGE_M = (2e-3, 1e-2)


def signed_body_distance(points, body, sdf) -> np.ndarray:
    """Signed distances (N,) float64 [m] from ``points`` (N, 3) [m] to the body's surface: exact
    unsigned distances (BVH, :func:`unsew.geometry.distance.point_mesh_distance`), negative where
    the body's SDF (a :class:`~unsew.body.sdf.BodySDF`) says the point is inside."""
    p = np.asarray(points, dtype=np.float64)
    d = point_mesh_distance(p, np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces))
    s, _ = sdf.query(torch.as_tensor(p))
    return np.where(s.detach().cpu().numpy() < 0, -d, d)


def target_gap(target_verts, body, sdf) -> float:
    """The GAP_PERCENTILE-th percentile [m] of :func:`signed_body_distance` of the target's
    vertices (V, 3) [m]: where the target's cloth rests on the body."""
    return float(np.percentile(signed_body_distance(target_verts, body, sdf), GAP_PERCENTILE))


def contact_for_target(cfg, target_verts, body, sdf, *, mode: str = CONTACT):
    """(cfg, info): ``cfg`` with its drape contact set from the target when ``mode`` (one of
    CONTACT_MODES, default :data:`CONTACT`) is "target" (threshold = the target's gap clamped to
    GAP_RANGE_M, stiffness CONTACT_STIFF), else unchanged; info, for metrics.json: {"mode",
    "gap_mm" (the measured gap, "target" only), "threshold_mm", "stiffness"} of the contact every
    drape of the fit uses."""
    if mode not in CONTACT_MODES:
        raise ValueError(f"contact mode must be one of {', '.join(CONTACT_MODES)}, got {mode!r}")
    d = cfg.drape
    info = {"mode": mode}
    if mode == "target":
        gap = target_gap(target_verts, body, sdf)
        thr = float(np.clip(gap, *GAP_RANGE_M))
        d = d.replace(contact_threshold=thr, contact_stiffness=CONTACT_STIFF)
        cfg = cfg.replace(drape=d)
        info["gap_mm"] = gap * 1e3
    info.update(threshold_mm=d.contact_threshold * 1e3, stiffness=d.contact_stiffness)
    return cfg, info
