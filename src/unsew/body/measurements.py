"""Body measurements that size the base patterns.

All lengths in metres. The defaults describe the embedded default body (anny, all six
phenotypes at 0.5, A-pose); :func:`unsew.body.measure.measure_body` measures any body.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace

__all__ = ["Measurements"]


@dataclass(frozen=True)
class Measurements:
    """Girths and lengths of a body [m]. Girths are horizontal circumferences (convex hull of the
    body's cross-section, as a tape measure reads them)."""

    height: float = 1.70  #: floor to top of head [m]
    bust: float = 0.94  #: girth at the fullest part of the chest [m]
    waist: float = 0.80  #: girth at the natural waist [m]
    hip: float = 0.98  #: girth at the fullest part of the hips [m]
    neck: float = 0.38  #: girth at the base of the neck [m]
    upper_arm: float = 0.30  #: girth of the upper arm near the armpit [m]
    thigh: float = 0.56  #: girth of the thigh below the crotch [m]
    shoulder_width: float = 0.40  #: between the shoulder joints' outer points [m]
    arm_length: float = 0.58  #: shoulder joint to wrist joint [m]
    leg_length: float = 0.80  #: hip joint to ankle joint [m]
    torso_length: float = 0.45  #: base of the neck to the natural waist, along the spine [m]
    waist_height: float = 1.03  #: floor to the natural waist [m]
    crotch_height: float = 0.78  #: floor to the crotch [m]
    neck_height: float = 1.45  #: floor to the base of the neck [m]

    def as_dict(self) -> dict[str, float]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> "Measurements":
        """Build from a mapping (e.g. a YAML file); unknown keys raise, missing keys keep defaults."""
        from unsew.errors import InputError

        names = {f.name for f in fields(cls)}
        unknown = set(d) - names
        if unknown:
            raise InputError(f"unknown measurement(s) {sorted(unknown)}; known: {sorted(names)}")
        vals = {}
        for k, v in d.items():
            try:
                v = float(v)
            except (TypeError, ValueError):
                raise InputError(f"measurement {k!r} must be a number in metres, got {v!r}") from None
            if not (0.05 < v < 3.0):
                raise InputError(f"measurement {k}={v} is implausible in metres (expected 0.05-3.0)")
            vals[k] = v
        return replace(cls(), **vals)
