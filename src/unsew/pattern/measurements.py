"""Body measurements that size the base patterns (read by ``unsew.pattern.base``; measured from a
body mesh by ``unsew.body.measure``).

All lengths in metres. The defaults describe the embedded default body (anny, all six
phenotypes at 0.5, A-pose) as measured by :func:`unsew.body.measure.measure_body`, which
measures any body (tests/body/test_measure.py checks the defaults against it).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace

from unsew.errors import InputError

__all__ = ["Measurements"]


@dataclass(frozen=True)
class Measurements:
    """Girths and lengths of a body [m]. Girths are horizontal circumferences (convex hull of the
    body's cross-section, as a tape measure reads them)."""

    height: float = 1.625  #: floor to top of head [m]
    bust: float = 0.858  #: girth at the fullest part of the chest [m]
    waist: float = 0.691  #: girth at the natural waist [m]
    hip: float = 0.901  #: girth at the fullest part of the hips [m]
    neck: float = 0.333  #: girth at the base of the neck [m]
    upper_arm: float = 0.273  #: girth of the upper arm near the armpit [m]
    thigh: float = 0.499  #: girth of the thigh below the crotch [m]
    shoulder_width: float = 0.386  #: between the shoulders' outer points at the acromion [m]
    arm_length: float = 0.480  #: shoulder joint to wrist joint [m]
    leg_length: float = 0.794  #: hip joint to ankle joint [m]
    torso_length: float = 0.358  #: base of the neck to the natural waist, along the spine [m]
    waist_height: float = 1.021  #: floor to the natural waist [m]
    crotch_height: float = 0.756  #: floor to the crotch [m]
    neck_height: float = 1.379  #: floor to the base of the neck [m]

    def as_dict(self) -> dict[str, float]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> "Measurements":
        """Build from a mapping (e.g. a YAML file); unknown keys raise, missing keys keep defaults."""
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
