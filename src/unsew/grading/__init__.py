"""Linear grading (paper 3.3, supplementary Algorithm 2): phase one of the fit.

- :mod:`unsew.grading.contours`: open contours located on the skeleton and paired source/target;
- :mod:`unsew.grading.curves`: 3D contours -> 2D open curves of the pattern;
- :mod:`unsew.grading.cloth`: cloth lengths from a contour to the top opening, on a drape and at rest;
- :mod:`unsew.grading.edit`: the control-point edit (move and widen, symmetric, no inversions);
- :mod:`unsew.grading.grade`: ``grade(pattern, body, verts, faces, GradingSettings) -> GradeResult``,
  the whole phase;
- :mod:`unsew.grading.alter`: known alterations of a pattern (targets for tests and benchmarks).

One import path per name: ``from unsew.grading.grade import grade, GradeResult``. This package
module imports nothing.
"""

__all__: list[str] = []
