"""Bending energy on hinge quads: dihedral angle of Bridson, Marino, Fedkiw 2005 (paper eq. 3).

For an interior edge e = x1 - x0 shared by triangles (x0, x1, x2) and (x1, x0, x3), with the
(unnormalised) normals n1 = e x (x2 - x0), n2 = (x3 - x0) x e, the signed bend angle about e is

    theta = atan2((n1 x n2) . e/|e|, n1 . n2)        (0 when flat; patterns are flat at rest)

and the energy, with Bridson's coefficient |e|^2/(A1+A2) (paper eq. 3: the force is
k |e|^2/(A1+A2) * (angle term) * u_i, u_i = d theta/d x_i),

    W = (D/2) * |e_r|^2 / (A1_r + A2_r) * (theta - theta0)^2,

with rest (pattern) edge length |e_r| and rest areas A_r, D = Gamma[4] the bending rigidity
[N*m]. We use theta - theta0 rather than Bridson's sin(theta/2) - sin(theta0/2): the same to
second order, and quadratic in theta.

Calibration (``bending_rest(calibrate=True)``, off by default). Plate theory stores D/2 kappa^2
per unit area in a sheet bent to a cylinder of curvature kappa. With Bridson's coefficient a
hinge energy gives that exactly on a grid whose edges run along the bend, but not in general: on
a grid it varies with the bend's direction, and on the quality meshes of unsew's panel mesher it
stores too much in every direction (the dihedral angle of a piecewise-linear sheet over a curved
one picks up the interpolant's slope error). The rest mesh tells how much: a uniform bend K (a
shallow quadratic sheet) opens at each hinge the angle a . (K_xx, K_xy, K_yy), the jump across
the edge of the interpolant's slope (computed on the hinge unfolded flat from its rest lengths,
so a seam's two panels count as one sheet). The mesh's factor is sum_e c_e <(a_e . k)^2> / sum_e
(A1 + A2)/3 over the hinges none of whose vertices lies on a panel's outline, averaged over unit
bends K = d d^T in every direction d, and every coefficient is divided by it (a mesh with no
such hinge keeps Bridson's coefficient). One factor per mesh, not per hinge: factors per vertex
neighbourhood fit a uniform bend as well but leave soft spots that a bending strip finds. The
factor corrects the average over directions: it makes the isotropic quality meshes of the panel
mesher right in every direction, not a grid, whose hinges answer differently along and across
(and more so with oblong cells). The factor depends on uv and is differentiated with it.
Measurements: docs/decisions/026-bending-calibration.md.

Gradient (Bridson 2003 / Tamstorf and Grinspun 2013), checked against autograd in the tests:
    d theta/dx2 = -|e| n1/|n1|^2,   d theta/dx3 = -|e| n2/|n2|^2,
    d theta/dx0 = -(1 - t1) g2 - (1 - t2) g3,   d theta/dx1 = -t1 g2 - t2 g3,
    t_i = (x_{i+1} - x0) . e / |e|^2 (projection of the opposite vertex on the edge).
Hessian for the system: the Gauss-Newton part 2 c (d theta/dx)(d theta/dx)^T, PSD (rank 1);
the term 2 c (theta - theta0) d2 theta/dx2 is left out of the matrix (not of the forces).

Clamped edges. A hinge stands for the curvature over its dual strip, a third of each of its two
triangles' height from the edge (the coefficient above). Where one triangle is rigid (its three
vertices pinned, as a clamp or a platform holds cloth) the strip on that side cannot bend: the
turn at the hinge is that of the free side's half strip alone, so the coefficient counts the free
triangle's area twice instead of both areas once. Without it a hinge chain clamped at one end
integrates the curvature by the left Riemann sum (the clamp's hinge bends over a whole cell):
a cantilever of 6 cells droops 1.36 times the beam formula, 1.03 times with it (the trapezoid
rule). Meshes without pinned vertices are unchanged.

Crushed triangles. |d theta/dx2| = 1/h1, h1 = |n1|/|e| the height of x2 over the edge, so a
triangle squashed onto its hinge edge (a fold pressed flat, cloth compressed into a crease) gives
forces growing as 1/h and a Gauss-Newton block as 1/h^2, until the assembled system, positive
definite in exact arithmetic, is indefinite in floating point and its Cholesky factorization
fails (docs/decisions/017-step-line-search.md). The heights
entering d theta/dx are therefore floored at HEIGHT_FLOOR times the triangle's size (the root
mean square of its edge lengths): below that (a triangle 1000 times flatter than wide) the
hinge's gradient and block stay those of a triangle of that height, bounded, while theta itself
is untouched. Any triangle of a sound drape is far above the floor, where nothing changes.
"""

from __future__ import annotations

import torch

from unsew.geometry.topology import boundary_vertices

__all__ = ["bending_rest", "energy_bending", "dihedral_angle"]

#: floor of |n|^2 [m^4] of a hinge's triangle normals: far below any real triangle's
#: ((1 mm)^4 = 1e-12), only a zero-area one is floored
_TINY = 1e-30

#: smallest height over hinge edge length [-] at which d theta/dx is taken exactly; flatter
#: (crushed) triangles use this height (module docstring, "Crushed triangles")
HEIGHT_FLOOR = 1e-3


def bending_rest(
    uv: torch.Tensor,
    faces_uv: torch.Tensor,
    hinge_faces,
    hinge_uv_edges,
    rest_area,
    *,
    rigid_faces=None,
    calibrate: bool = False,
):
    """Per-hinge rest coefficient c [-] (dimensionless), shape (H,): Bridson's
    |e_r|^2 / (A1_r + A2_r), with ``calibrate`` over the mesh's own uniform-bend factor (module
    docstring, "Calibration"; off by default: the fit's phase-two checks were tuned on Bridson's
    scale, docs/decisions/026-bending-calibration.md).

    Args:
        uv: rest positions [m], (Nu, 2). faces_uv: (F, 3) int64.
        hinge_faces: (H, 2) int64; hinge_uv_edges: (H, 4) int64 (see model.build_hinges).
        rest_area: rest triangle areas [m^2], (F,).
        rigid_faces: (F,) bool, faces that cannot bend (all three vertices pinned: a clamp), or
            None. A hinge between a rigid face and a free one takes the free face's area twice
            (module docstring, "Clamped edges").
    """
    ea = (uv[hinge_uv_edges[:, 1]] - uv[hinge_uv_edges[:, 0]]).pow(2).sum(-1)
    eb = (uv[hinge_uv_edges[:, 3]] - uv[hinge_uv_edges[:, 2]]).pow(2).sum(-1)
    e2 = 0.5 * (ea + eb)  # the two sides of a seam may differ slightly: take the mean
    a1, a2 = rest_area[hinge_faces[:, 0]], rest_area[hinge_faces[:, 1]]
    coef = e2 / (a1 + a2)
    if calibrate and coef.shape[0]:
        coef = coef / _uniform_bend_factor(uv, faces_uv, hinge_faces, hinge_uv_edges, coef, a1 + a2)
    if rigid_faces is not None:
        r1, r2 = rigid_faces[hinge_faces[:, 0]], rigid_faces[hinge_faces[:, 1]]
        coef = torch.where(r1 ^ r2, coef * (a1 + a2) / torch.where(r1, a2, a1), coef)
    return coef


#: average of k k^T over the unit bends K = d d^T (d at every angle), k = (K_xx, K_xy, K_yy)
_BEND_AVERAGE = ((3 / 8, 0.0, 1 / 8), (0.0, 1 / 8, 0.0), (1 / 8, 0.0, 3 / 8))


def _pl_gradients(p: torch.Tensor) -> torch.Tensor:
    """Gradients [1/m] of the three barycentric functions of triangles p (H, 3, 2): (H, 3, 2)."""
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    g1 = torch.stack([e2[:, 1], -e2[:, 0]], -1) / det[:, None]
    g2 = torch.stack([-e1[:, 1], e1[:, 0]], -1) / det[:, None]
    return torch.stack([-g1 - g2, g1, g2], 1)


def _uniform_bend_factor(uv, faces_uv, hinge_faces, hinge_uv_edges, coef, area2):
    """Factor [-] (scalar tensor) by which Bridson's hinge energy (``coef`` (H,), ``area2`` = A1 + A2
    (H,) [m^2]) exceeds D/2 kappa^2 per unit area for a uniform bend of the rest mesh, averaged
    over the bend's direction and the hinges off the panels' outlines (module docstring,
    "Calibration")."""
    fa, fb = faces_uv[hinge_faces[:, 0]], faces_uv[hinge_faces[:, 1]]
    i0, i1 = hinge_uv_edges[:, 0], hinge_uv_edges[:, 1]
    i2 = fa.sum(1) - i0 - i1  # face 1's vertex off the edge
    i3 = fb.sum(1) - hinge_uv_edges[:, 2] - hinge_uv_edges[:, 3]
    # the hinge unfolded flat in its own frame (edge along x from the origin), from rest lengths,
    # so that a seam's two panels meet: x2 above the edge, x3 below
    e = uv[i1] - uv[i0]
    el = e.norm(dim=-1)
    ex = e / el[:, None]
    q2 = uv[i2] - uv[i0]
    p2 = torch.stack([(q2 * ex).sum(-1), (ex[:, 0] * q2[:, 1] - ex[:, 1] * q2[:, 0]).abs()], -1)
    eb = uv[hinge_uv_edges[:, 3]] - uv[hinge_uv_edges[:, 2]]  # face 2's copy of the edge
    ebl = eb.norm(dim=-1)
    q3 = uv[i3] - uv[hinge_uv_edges[:, 3]]  # from face 2's copy of x0 (the edge runs x1 -> x0 there)
    ebx = -eb / ebl[:, None]
    p3 = torch.stack([(q3 * ebx).sum(-1), -(ebx[:, 0] * q3[:, 1] - ebx[:, 1] * q3[:, 0]).abs()], -1)
    zero = torch.zeros_like(p2)
    p1 = torch.stack([el, torch.zeros_like(el)], -1)
    k = torch.tensor(_BEND_AVERAGE, dtype=uv.dtype, device=uv.device)

    def slope(p):  # (H, 3, 2) -> (H, 3): d/dy of the interpolant of (x^2/2, x y, y^2/2)
        vals = torch.stack([0.5 * p[..., 0] ** 2, p[..., 0] * p[..., 1], 0.5 * p[..., 1] ** 2], -1)
        return torch.einsum("hi,hik->hk", _pl_gradients(p)[..., 1], vals)

    # the angle a uniform bend K opens at the hinge is the jump of the interpolant's slope across
    # the edge: a . (K_xx, K_xy, K_yy), a (H, 3) (exact for a shallow quadratic sheet)
    a = slope(torch.stack([zero, p1, p2], 1)) - slope(torch.stack([zero, p1, p3], 1))
    num = coef * torch.einsum("hk,kl,hl->h", a, k, a)  # (H,) energy / (D/2 kappa^2), direction-averaged
    share = area2 / 3.0  # the area a hinge stands for
    # only hinges away from the panels' outlines: a border (free edge or seam) has no hinge on it,
    # so the hinges beside it see a uniform bend through a lopsided stencil; a mesh with no
    # interior hinge (a strip one cell wide) is left as it is
    outline = torch.from_numpy(boundary_vertices(faces_uv.detach().cpu().numpy(), uv.shape[0]))
    inner = ~outline.to(uv.device)[torch.stack([i0, i1, i2, i3], 1)].any(1)
    if not bool(inner.any()):
        return torch.ones((), dtype=uv.dtype, device=uv.device)
    return num[inner].sum() / share[inner].sum()


def _cross(a, b):
    return torch.linalg.cross(a, b, dim=-1)


def dihedral_angle(x: torch.Tensor, hinges: torch.Tensor):
    """Signed bend angle theta [rad] of each hinge, shape (H,), and its gradient (H, 4, 3) [rad/m].

    x: positions [m] (N, 3); hinges: (H, 4) int64 (x0, x1 edge; x2, x3 opposite)."""
    X = x[hinges]  # (H, 4, 3)
    x0, x1, x2, x3 = X.unbind(1)
    e = x1 - x0
    el = e.norm(dim=-1)
    n1 = _cross(e, x2 - x0)
    n2 = _cross(x3 - x0, e)
    # a triangle flat on a line (zero area) has no normal: its angle reads 0 and its gradient
    # (el / |n|^2) n is 0 rather than 0/0, so a degenerate start (a panel folded flat by its
    # placement) bends nothing until it opens, instead of a NaN force at step 0
    # |n|^2 = (h |e|)^2 with h floored at HEIGHT_FLOOR * (the triangle's rms edge length)
    s1 = (el * el + ((x2 - x0) ** 2).sum(-1) + ((x2 - x1) ** 2).sum(-1)) / 3.0
    s2 = (el * el + ((x3 - x0) ** 2).sum(-1) + ((x3 - x1) ** 2).sum(-1)) / 3.0
    n1s = torch.maximum((n1 * n1).sum(-1), (HEIGHT_FLOOR**2 * el * el * s1).clamp_min(_TINY))
    n2s = torch.maximum((n2 * n2).sum(-1), (HEIGHT_FLOOR**2 * el * el * s2).clamp_min(_TINY))
    elc = el.clamp_min(_TINY)  # a zero-length edge (two vertices on one point): the same reading
    theta = torch.atan2((_cross(n1, n2) * e).sum(-1) / elc, (n1 * n2).sum(-1))
    g2 = -(el / n1s)[:, None] * n1
    g3 = -(el / n2s)[:, None] * n2
    e2 = (el * el).clamp_min(_TINY)
    t1 = ((x2 - x0) * e).sum(-1) / e2
    t2 = ((x3 - x0) * e).sum(-1) / e2
    g0 = -(1 - t1)[:, None] * g2 - (1 - t2)[:, None] * g3
    g1 = -t1[:, None] * g2 - t2[:, None] * g3
    return theta, torch.stack([g0, g1, g2, g3], 1)


def energy_bending(x, hinges, coef, gamma, *, theta0=None, hessian: bool = True, parts: bool = False):
    """Bending energy, per-hinge gradient and Gauss-Newton Hessian.

    Args:
        x: positions [m], (N, 3) float64. hinges: (H, 4) int64.
        coef: (H,) from :func:`bending_rest`. gamma: (5,), uses D = gamma[4] [N*m].
        theta0: rest angles [rad] (H,) or None (flat).
        parts: return the Hessian's factors (g (H, 12) [rad/m], s (H,) [N*m]) with
            hess = s g g^T, for ``assembly.assemble_outer``, instead of blocks.

    Returns:
        energy [J] scalar; grad (H, 4, 3) [N]; hess (H, 12, 12) [N/m] PSD or None.
    """
    if hinges.shape[0] == 0:
        z = x.new_zeros(())
        if parts and hessian:
            return z, x.new_zeros(0, 4, 3), (x.new_zeros(0, 12), x.new_zeros(0))
        return z, x.new_zeros(0, 4, 3), (x.new_zeros(0, 12, 12) if hessian else None)
    theta, dth = dihedral_angle(x, hinges)
    d = theta if theta0 is None else theta - theta0
    c = 0.5 * gamma[4] * coef  # (H,) [N*m]
    energy = (c * d * d).sum()
    grad = (2.0 * c * d)[:, None, None] * dth
    if not hessian:
        return energy, grad, None
    gf = dth.reshape(-1, 12)
    if parts:
        return energy, grad, (gf, 2.0 * c)
    hess = (2.0 * c)[:, None, None] * gf[:, :, None] * gf[:, None, :]
    return energy, grad, hess
