"""A design space of garments: discrete structural choices and a few measures
(:class:`Design`), drafted for a body into a sewing pattern (:func:`draft`).

The library's 16 bases (:mod:`unsew.pattern.base`) are points of this space
(:func:`design_of_base`); :func:`design_space` lists a garment type's candidates. Every draft is
a :class:`~unsew.pattern.model.Pattern` placed around the body like the bases, which validates,
meshes and saves as GarmentCode JSON. docs/design_space.md describes the choices.

Example::

    from unsew.pattern.design import Design, draft
    p = draft(Design(garment="dress", waist_seam=True, skirt="circle", panels=6, sleeves="long"))
"""

from unsew.pattern.design._choices import (
    CHOICES,
    CIRCLE_FRACTIONS,
    GARMENTS,
    LENGTHS,
    STRAPLESS_DROP,
    TOP_DROP_RANGE,
    TOP_LENGTH_MIN,
    Design,
    design_name,
    design_of_base,
    design_space,
)
from unsew.pattern.design._draft import draft, length_to

__all__ = [
    "Design",
    "CHOICES",
    "CIRCLE_FRACTIONS",
    "GARMENTS",
    "LENGTHS",
    "STRAPLESS_DROP",
    "TOP_DROP_RANGE",
    "TOP_LENGTH_MIN",
    "draft",
    "design_space",
    "design_of_base",
    "design_name",
    "length_to",
]
