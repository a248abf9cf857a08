"""Named tolerances, in one place (STYLE.md habit 10). SI units."""

__all__ = [
    "GEOM_EPS",
    "SYMMETRY_REL_TOL",
    "STITCH_LENGTH_WARN_REL",
    "COLLISION_THICKNESS",
    "REBUILD_ATOL",
    "FLAT_CURVATURE_TOL",
    "MIN_TRIANGLE_QUALITY",
    "BODY_MIRROR_TOL",
]

#: Lengths below this are treated as zero [m].
GEOM_EPS = 1e-9

#: Symmetry detection accepts an alignment whose largest point residual is below this fraction
#: of the aligned points' RMS radius (Algorithm 1's epsilon, made scale-free; the largest residual
#: rather than the RMS, so one differing curve such as a deeper neckline breaks a pair).
SYMMETRY_REL_TOL = 0.02

#: Stitched edges whose lengths differ by more than this fraction get a warning.
STITCH_LENGTH_WARN_REL = 0.05

#: Collision thickness delta of paper eq. 4 [m].
COLLISION_THICKNESS = 1e-3

#: Control points rebuilt from K must equal the originals to this absolute tolerance [m].
REBUILD_ATOL = 1e-9

#: A mesh whose area-weighted mean |H| times sqrt(area) is below this (dimensionless) is flat:
#: its curvature weights are exactly 1 (unsew.losses.curvature).
FLAT_CURVATURE_TOL = 1e-8

#: A control point edit (fit step, grading edit) may not make a pattern triangle flatter than
#: this height over longest edge [-]: ten times the simulator's refusal threshold
#: (unsew.sim.integrator); a fit of the noisy t-shirt target once stepped to 4e-5 and the next
#: drape refused the pattern.
MIN_TRIANGLE_QUALITY = 1e-3

#: A body whose every vertex has a mirror image (x -> 2c - x) within this distance of a vertex is
#: left-right symmetric [m]: it is made exactly symmetric when loaded (unsew.body.body.symmetrize)
#: and its SDF grid is built symmetric. The default anny body is off by 0.41 mm (float32 storage).
BODY_MIRROR_TOL = 1e-3
