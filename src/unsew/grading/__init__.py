"""Linear grading (paper 3.3, supplementary Algorithm 2): phase one of the fit.

- :mod:`~unsew.grading.contours`: open contours located on the skeleton and paired source/target;
- :mod:`~unsew.grading.curves`: 3D contours -> 2D open curves of the pattern;
- :mod:`~unsew.grading.edit`: the control-point edit (move and widen, symmetric, no inversions);
- :mod:`~unsew.grading.grade`: ``grade(...) -> GradeResult``, the whole phase;
- :mod:`~unsew.grading.alter`: known alterations of a pattern (targets for tests and benchmarks).

Import from the submodules (``from unsew.grading.grade import grade``); this package imports
nothing heavy.
"""

__all__ = ["grade", "GradeResult"]


def __getattr__(name):
    if name in __all__:
        from unsew.grading import grade as _g

        return getattr(_g, name)
    raise AttributeError(f"module 'unsew.grading' has no attribute {name!r}")
