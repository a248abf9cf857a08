"""Where the fit's drapes meet the body (``contact``): as unsew drapes by default, or at the gap the
target's own cloth keeps from the body.

A simulator rests cloth at its own distance from the body: newton's at its particle radius (4 mm
on the foreign benchmark's targets), unsew's where the repulsion of :mod:`unsew.sim.energies.contact`
(kc 1e7 N/m^4 below 5 mm) balances what the cloth presses with, as near as the 1 mm collision
thickness where it is pulled tight. A band pulled round a waist 3 mm nearer the body is a loop
2 pi x 3 mm = 1.9 cm shorter, and phase two lengthens the pattern to close that gap
(docs/benchmarks.md, "The cloth's gap to the body"). With ``contact: target`` the fit reads the gap
from the target and body it is given and drapes with a contact that rests the cloth there: the
threshold at the gap, the stiffness CONTACT_STIFF, under which a pressing cloth sinks well under a
millimetre into the zone (p = kc s^2: 1 kPa, a band's pressure, sinks 1 mm at 1e9).
"""

from __future__ import annotations

import numpy as np
import torch

from unsew.geometry.distance import point_mesh_distance

__all__ = ["CONTACT_MODES", "CONTACT_STIFF", "GAP_PERCENTILE", "GAP_RANGE_M", "target_gap", "contact_for_target"]

#: What the fit does with the body contact (``contact``).
CONTACT_MODES = ("default", "target")

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


def target_gap(target_verts, body, sdf) -> float:
    """The GAP_PERCENTILE-th percentile of the signed distances [m] from the target's vertices
    (V, 3) [m] to the body's surface: exact unsigned distances (BVH), negative where the body's
    SDF says the vertex is inside."""
    p = np.asarray(target_verts, dtype=np.float64)
    d = point_mesh_distance(p, np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces))
    s, _ = sdf.query(torch.as_tensor(p))
    d = np.where(s.detach().cpu().numpy() < 0, -d, d)
    return float(np.percentile(d, GAP_PERCENTILE))


def contact_for_target(cfg, target_verts, body, sdf):
    """(cfg, info): ``cfg`` with its drape contact set from the target when ``cfg.contact`` is
    "target" (threshold = the target's gap clamped to GAP_RANGE_M, stiffness CONTACT_STIFF), else
    unchanged; info, for metrics.json: {"mode", "gap_mm" (the measured gap, "target" only),
    "threshold_mm", "stiffness"} of the contact every drape of the fit uses."""
    d = cfg.drape
    info = {"mode": cfg.contact}
    if cfg.contact == "target":
        gap = target_gap(target_verts, body, sdf)
        thr = float(np.clip(gap, *GAP_RANGE_M))
        d = d.replace(contact_threshold=thr, contact_stiffness=CONTACT_STIFF)
        cfg = cfg.replace(drape=d)
        info["gap_mm"] = gap * 1e3
    info.update(threshold_mm=d.contact_threshold * 1e3, stiffness=d.contact_stiffness)
    return cfg, info
