"""Where the base patterns sit around a body: every world-frame number in one place.

World frame (shared/FORMATS.md): metres, Y up, the body faces +Z, its left at +X, feet at
y = 0, centre line x = 0, torso centred near z = 0. All heights and depths here are derived
from :class:`~unsew.pattern.measurements.Measurements`; the few proportions that are not
measurements (shoulder slope, armhole depth, torso depth per girth, A-pose arm angle) are named
constants below.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from unsew.pattern.measurements import Measurements

__all__ = ["BodyFrame", "body_frame"]

#: Drop from the base of the neck to the shoulder tip [m].
SHOULDER_DROP = 0.045
#: Armhole depth below the shoulder tip as a fraction of the bust girth (plus a constant) [m].
ARMHOLE_DEPTH_PER_BUST = 0.125
ARMHOLE_DEPTH_CONST = 0.08
#: Torso depth (front to back) per girth: an ellipse of girth G and aspect 0.7 is about G/3.35 deep.
DEPTH_PER_GIRTH = 1.0 / 3.35
#: Clearance between a panel laid flat and the body surface it covers [m].
CLEARANCE = 0.05
#: The hips' fullest girth sits this fraction of the way from the waist down to the crotch.
HIP_DROP_FRACTION = 0.7
#: A-pose: arms hang this many degrees below horizontal (the default anny body's "A" pose).
ARM_ANGLE_DEG = 45.0


@dataclass(frozen=True)
class BodyFrame:
    """Landmarks of a body in the world frame [m] (heights are y, depths are z)."""

    neck_y: float  #: base of the neck
    shoulder_y: float  #: shoulder tip
    shoulder_x: float  #: shoulder tip, |x|
    armpit_y: float  #: bottom of the armhole
    waist_y: float  #: natural waist
    hip_y: float  #: fullest part of the hips
    crotch_y: float  #: crotch
    chest_z: float  #: where a front torso panel is laid (z > 0); back panels at -chest_z
    hip_z: float  #: where front lower-body panels are laid (z > 0); back panels at -hip_z
    arm_angle: float  #: arms' angle below horizontal [rad]


def body_frame(m: Measurements | None = None) -> BodyFrame:
    """The :class:`BodyFrame` of a body with measurements ``m`` (default: the default body)."""
    m = m or Measurements()
    shoulder_y = m.neck_height - SHOULDER_DROP
    return BodyFrame(
        neck_y=m.neck_height,
        shoulder_y=shoulder_y,
        shoulder_x=m.shoulder_width / 2,
        armpit_y=shoulder_y - (ARMHOLE_DEPTH_PER_BUST * m.bust + ARMHOLE_DEPTH_CONST),
        waist_y=m.waist_height,
        hip_y=m.waist_height - HIP_DROP_FRACTION * (m.waist_height - m.crotch_height),
        crotch_y=m.crotch_height,
        chest_z=m.bust * DEPTH_PER_GIRTH / 2 + CLEARANCE,
        hip_z=m.hip * DEPTH_PER_GIRTH / 2 + CLEARANCE,
        arm_angle=math.radians(ARM_ANGLE_DEG),
    )
