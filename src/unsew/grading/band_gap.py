"""A waistband's target loop read as unsew's contact would drape it (grading's ``band_gap``).

Every simulator rests cloth at its own distance from the body: newton's at its particle radius
(4 mm), unsew's as near as its collision thickness (1 mm) where the cloth is pulled tight. A band
pressed round a waist is then a loop 2 pi (4 - 1) mm, about 1.9 cm, longer in the target than the
same cloth in unsew's drape. Graded to the target's loop as measured, the band comes out that much
looser than the one unsew needs to hang where the target's hangs, and on a waist with no shelf
below it, it slides down until a girth holds it.

With ``band_gap="target"`` the target loops that press on the body all round have that excess
read off before a band is graded to them: ``2 pi (g - OWN_GAP)``, g the gap the target's cloth
keeps where it presses (the 1st percentile of its vertices' distances to the body, no more than
the loop's own median distance). Loops farther from the body than ``g + PRESSED_TOL`` (a loose
band, a hem) are read as they are; only waistband items use the reading, and only on a garment
that hangs from its band (:func:`hangs_from_band`: a skirt; trousers and shorts are held up by
their crotch as well). Why the default: docs/decisions/009.
"""

from __future__ import annotations

import numpy as np

from unsew.geometry.distance import point_mesh_distance
from unsew.tolerances import COLLISION_THICKNESS

__all__ = [
    "BAND_GAP_MODES",
    "OWN_GAP",
    "PRESSED_TOL",
    "GAP_PERCENTILE",
    "pressed_loop_excess",
    "hangs_from_band",
]

#: The choices of ``GradingSettings.band_gap``: the target's band loops as measured, or less the
#: excess the target's contact gap adds.
BAND_GAP_MODES = ("none", "target")

#: How near unsew's cloth rests where it is pulled tight round the body [m]: the collision
#: thickness (its drapes' 1st percentile of distances to the body: 0.1-2.7 mm, median 1.0).
OWN_GAP = COLLISION_THICKNESS

#: A target loop presses on the body when its median distance to it is within the target's gap
#: plus this [m]: the top loops of the banded foreign targets read 3.8-4.0 mm against gaps of
#: 3.5-4.0 (``python -m benchmarks band_gap`` at 81f6fbb), hems and leg openings 8 mm and more.
PRESSED_TOL = 2e-3

#: Percentile of the target vertices' distances to the body read as its cloth's contact gap [-]
#: (as :data:`unsew.fit.contact.GAP_PERCENTILE`).
GAP_PERCENTILE = 1.0


def pressed_loop_excess(target_verts, contours, body) -> dict[int, float]:
    """Target contour index -> the length [m] its loop owes to the target's contact gap, for each
    contour that presses on the body (its median distance within the gap + :data:`PRESSED_TOL`).

    target_verts: (V, 3) float64 [m]; contours: the target's placed contours
    (:class:`~unsew.grading.contours.PlacedContour`); body: the wearer (verts, faces).
    The excess is ``2 pi (min(g, median) - OWN_GAP)``, g the :data:`GAP_PERCENTILE`-th percentile
    of every target vertex's distance to the body; none when that is below OWN_GAP (a target draped
    by unsew itself, or lying in the body).
    """
    tv = np.asarray(target_verts, dtype=np.float64)
    d = point_mesh_distance(tv, np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces))
    gap = float(np.percentile(d, GAP_PERCENTILE))
    out: dict[int, float] = {}
    for c in contours:
        med = float(np.median(d[np.asarray(c.contour.indices)]))
        if med > gap + PRESSED_TOL:
            continue
        excess = 2.0 * np.pi * (min(gap, med) - OWN_GAP)
        if excess > 0:
            out[int(c.index)] = float(excess)
    return out


def hangs_from_band(contours) -> bool:
    """Whether the garment whose placed contours are ``contours`` hangs from its top alone: none
    of its open contours lies on a leg (a skirt, not trousers or shorts, whose crotch also holds
    them)."""
    return not any(str(c.part).endswith("leg") for c in contours)
