"""Former home of :class:`unsew.pattern.measurements.Measurements`, kept so that callers not yet
moved over (``unsew.commands._pattern_new``) still import; new code imports it from
``unsew.pattern.measurements`` (pattern sizes from measurements and knows no body)."""

from unsew.pattern.measurements import Measurements

__all__ = ["Measurements"]
