"""Membrane (stretch/shear) energy: linear orthotropic stress on the Green strain (paper eq. 2).

Formula (Saint-Venant-Kirchhoff-type orthotropic membrane, as in ARCSim / [SB12]):
for a triangle with 2D rest corners u_i (pattern, [m]) and 3D corners x_i,

    D_m = [u_1 - u_0, u_2 - u_0] (2x2),  F = [x_1 - x_0, x_2 - x_0] D_m^-1 (3x2),
    E = (F^T F - I) / 2   (Green strain),
    eps = (E_uu, E_vv, 2 E_uv)       (engineering shear: gamma_uv = 2 E_uv),
    W = A_rest / 2 * eps^T H eps,   H = [[H00, H01, 0], [H01, H11, 0], [0, 0, H22]]  [N/m].

Stress (2nd Piola-Kirchhoff per unit width) s = H eps, S = [[s0, s2], [s2, s1]]. With
B = [[-1, -1], [1, 0], [0, 1]] D_m^-1 (3x2), F = sum_i x_i B_i^T and

    dW/dx_k = A (F S B_k)                        (gradient, per corner),
    d2W/dx dx = A (G^T H G + (B S B^T) kron I3)  (Hessian),

with G (3 strains x 9 dofs): G_0k = B_k0 F_0, G_1k = B_k1 F_1, G_2k = B_k0 F_1 + B_k1 F_0.
The first term is PSD (H is PD). The second is PSD iff S is; under compression it is not, so
for the system matrix we replace S by its PSD part S+ (closed form for 2x2: both eigenvalues
kept, one kept via lambda+ (S - lambda- I)/(lambda+ - lambda-), or none), which keeps the
projected Hessian a continuous, almost-everywhere differentiable function of x, uv and H.
"""

from __future__ import annotations

import torch

__all__ = ["membrane_rest", "energy_membrane", "stiffness_matrix"]

_B0 = ((-1.0, -1.0), (1.0, 0.0), (0.0, 1.0))


def stiffness_matrix(gamma: torch.Tensor) -> torch.Tensor:
    """H (3, 3) [N/m] from Gamma (5,) = (H00, H01, H11, H22, k)."""
    z = torch.zeros((), dtype=gamma.dtype, device=gamma.device)
    return torch.stack(
        [
            torch.stack([gamma[0], gamma[1], z]),
            torch.stack([gamma[1], gamma[2], z]),
            torch.stack([z, z, gamma[3]]),
        ]
    )


def membrane_rest(uv: torch.Tensor, faces_uv: torch.Tensor):
    """Rest quantities of each triangle.

    Args:
        uv: rest vertex positions [m], shape (Nu, 2), float64.
        faces_uv: (F, 3) int64 triangles into uv.

    Returns:
        area: signed-free rest areas [m^2], shape (F,).
        B: (F, 3, 2) [1/m] maps corners to the deformation gradient, F = X^T B.
        signed: signed rest areas [m^2], shape (F,) (negative = clockwise in 2D).
    """
    u = uv[faces_uv]  # (F, 3, 2)
    dm = torch.stack([u[:, 1] - u[:, 0], u[:, 2] - u[:, 0]], dim=-1)  # (F, 2, 2) columns
    det = dm[:, 0, 0] * dm[:, 1, 1] - dm[:, 0, 1] * dm[:, 1, 0]
    inv = (
        torch.stack(
            [torch.stack([dm[:, 1, 1], -dm[:, 0, 1]], -1), torch.stack([-dm[:, 1, 0], dm[:, 0, 0]], -1)], -2
        )
        / det[:, None, None]
    )
    b0 = torch.tensor(_B0, dtype=uv.dtype, device=uv.device)
    B = torch.einsum("ia,fab->fib", b0, inv)
    return 0.5 * det.abs(), B, 0.5 * det


def _psd2(S: torch.Tensor) -> torch.Tensor:
    """PSD part of symmetric 2x2 matrices (F, 2, 2), differentiable away from eigenvalue 0."""
    a, b, c = S[:, 0, 0], S[:, 1, 1], S[:, 0, 1]
    det = a * b - c * c
    tr = a + b
    mixed = det < 0
    disc = 0.25 * (a - b) ** 2 + c * c
    root = torch.sqrt(torch.where(mixed, disc, torch.ones_like(disc)))
    lp = 0.5 * tr + root
    lm = 0.5 * tr - root
    eye = torch.eye(2, dtype=S.dtype, device=S.device)
    one = (lp / torch.where(mixed, lp - lm, torch.ones_like(lp)))[:, None, None] * (
        S - lm[:, None, None] * eye
    )
    keep_all = (det >= 0) & (tr >= 0)
    zero = torch.zeros_like(S)
    return torch.where(keep_all[:, None, None], S, torch.where(mixed[:, None, None], one, zero))


def energy_membrane(
    x, faces, area, B, gamma, *, hessian: bool = True, project: bool = True, parts: bool = False
):
    """Membrane energy, per-corner gradient and (projected) per-element Hessian.

    Args:
        x: vertex positions [m], shape (N, 3), float64.
        faces: (F, 3) int64 into x.
        area: rest areas [m^2], shape (F,) (from :func:`membrane_rest`).
        B: (F, 3, 2) [1/m] (from :func:`membrane_rest`).
        gamma: (5,) Gamma; uses H00, H01, H11, H22 [N/m].
        hessian: compute the Hessian.
        project: replace the stress term by its PSD part (for the system matrix).
        parts: return the Hessian's factors (G (F, 3, 9), H (3, 3), P (F, 3, 3)) with
            hess = area (G^T H G + P kron I3), for ``assembly.assemble_membrane``, instead of blocks.

    Returns:
        energy: scalar [J]; grad: dW/dx per corner [N], shape (F, 3, 3) (corner, xyz);
        hess: (F, 9, 9) [N/m] (dof order corner-major, xyz minor) or None.
    """
    H = stiffness_matrix(gamma)
    X = x[faces]  # (F, 3 corners, 3 xyz)
    Fd = torch.einsum("fic,fia->fca", X, B)  # (F, 3 xyz, 2)
    C = torch.einsum("fca,fcb->fab", Fd, Fd)
    eps = torch.stack([0.5 * (C[:, 0, 0] - 1.0), 0.5 * (C[:, 1, 1] - 1.0), C[:, 0, 1]], -1)  # (F, 3)
    s = eps @ H  # H symmetric: (F, 3) stresses [N/m]
    energy = 0.5 * (area * (eps * s).sum(-1)).sum()
    S = torch.stack([torch.stack([s[:, 0], s[:, 2]], -1), torch.stack([s[:, 2], s[:, 1]], -1)], -2)  # (F,2,2)
    grad = area[:, None, None] * torch.einsum("fca,fab,fkb->fkc", Fd, S, B)  # (F, 3 corners, 3 xyz)
    if not hessian:
        return energy, grad, None
    F0, F1 = Fd[:, :, 0], Fd[:, :, 1]  # (F, 3)
    B0, B1 = B[:, :, 0], B[:, :, 1]  # (F, 3)
    G = torch.stack(
        [
            B0[:, :, None] * F0[:, None, :],
            B1[:, :, None] * F1[:, None, :],
            B0[:, :, None] * F1[:, None, :] + B1[:, :, None] * F0[:, None, :],
        ],
        1,
    ).reshape(-1, 3, 9)  # (F, 3 strains, 9 dofs)
    Sp = _psd2(S) if project else S
    bsb = torch.einsum("fka,fab,flb->fkl", B, Sp, B)  # (F, 3, 3)
    if parts:
        return energy, grad, (G, H, bsb)
    gn = torch.einsum("fmi,mn,fnj->fij", G, H, G)
    eye3 = torch.eye(3, dtype=x.dtype, device=x.device)
    geo = (bsb[:, :, None, :, None] * eye3[None, None, :, None, :]).reshape(-1, 9, 9)
    hess = area[:, None, None] * (gn + geo)
    return energy, grad, hess
