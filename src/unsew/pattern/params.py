"""Pattern parameters: the effective control points K and the linear maps K -> control points -> U
(paper 3.2 "Parameterization"/"Symmetry detection" and 3.3, the mean value coordinates paragraph).

Everything is one precomputed affine map, built once per pattern and mesh:

    C = L_c @ K + b_c      all control points from K (symmetry rebuild, :mod:`unsew.pattern.symmetry`)
    U = L_u @ K + b_u      all 2D rest vertices of the panel meshes

(arrays flattened in xy order). ``L_u = A @ L_c``, ``b_u = A @ b_c`` where A moves the mesh with
its control points:

- outline vertices on the curve between consecutive control points c_a, c_b keep their
  coordinates in the curve's frame (origin c_a, axis c_b - c_a). In complex numbers
  ``u = c_a + z (c_b - c_a) = (1 - z) c_a + z c_b`` with z fixed at rest, a similarity that is
  linear in the two control points;
- interior vertices follow the panel's outline by mean value coordinates
  (:func:`unsew.pattern.mvc.mean_value_coordinates`), computed once at rest.

So ``uv(K)`` is differentiable (it is a matrix product) and K0 gives back the rest mesh exactly.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from unsew.errors import PatternError
from unsew.pattern.controls import ControlPoints, find_control_points
from unsew.pattern.model import Pattern
from unsew.pattern.mvc import mean_value_coordinates
from unsew.pattern.symmetry import Symmetry, detect_symmetry

__all__ = ["PatternParams", "check_inverted", "deformation_matrix"]


def _cblock(w: complex) -> np.ndarray:
    """Real 2x2 matrix of multiplication by the complex number w."""
    return np.array([[w.real, -w.imag], [w.imag, w.real]])


def _control_uv_index(pattern: Pattern, mesh, controls: ControlPoints) -> np.ndarray:
    """uv index (Nc,) int64 of each control point (a panel vertex is the first sample of the
    edge that starts there)."""
    out = np.empty(len(controls), dtype=np.int64)
    for g in range(len(controls)):
        name = controls.panel_names[int(controls.panel[g])]
        panel = pattern.panels[name]
        e = next(i for i, ed in enumerate(panel.edges) if ed.start == int(controls.vertex[g]))
        out[g] = mesh.edge_verts[(name, e)][0]
    return out


def deformation_matrix(
    mesh, controls: ControlPoints, control_uv: np.ndarray, p: int
) -> tuple[np.ndarray, np.ndarray]:
    """The map from panel p's control points to its mesh vertices (per-curve frames on the
    outline, mean value coordinates inside).

    mesh: the GarmentMesh. controls: the pattern's control points. control_uv: (Nc,) int64 uv
    index of each control point. p: panel index.

    Returns (rows (n_p,) int64 uv indices of the panel's vertices, A (2 n_p, 2 c_p) float64) with
    ``uv[rows].reshape(-1) = A @ C[panel's control points].reshape(-1)`` at rest.
    """
    loop = mesh.boundary_loop(p)
    inner = mesh.interior(p)
    nb = len(loop)
    cidx = controls.of_panel(p)
    cpos = (control_uv[cidx] - loop[0]).astype(np.int64)  # positions along the outline loop
    order = np.argsort(cpos)
    if not np.array_equal(order, np.arange(len(cpos))):  # pragma: no cover - controls are CCW by construction
        raise AssertionError("control points are not in outline order")
    uvz = mesh.uv[:, 0] + 1j * mesh.uv[:, 1]
    nc = len(cidx)
    A_b = np.zeros((nb, 2, 2 * nc))
    for j in range(nc):
        a_pos, b_pos = int(cpos[j]), int(cpos[(j + 1) % nc])
        span = (b_pos - a_pos) % nb or nb
        ca, cb = uvz[loop[a_pos]], uvz[loop[b_pos]]
        for k in range(span):
            q = (a_pos + k) % nb
            z = (uvz[loop[q]] - ca) / (cb - ca)
            jn = (j + 1) % nc
            A_b[q, :, 2 * j : 2 * j + 2] += _cblock(1 - z)
            A_b[q, :, 2 * jn : 2 * jn + 2] += _cblock(z)
    if len(inner):
        W = mean_value_coordinates(mesh.uv[inner], mesh.uv[loop])  # (ni, nb)
        A_i = np.einsum("ib,bkc->ikc", W, A_b)
        A = np.concatenate([A_b, A_i], axis=0)
        rows = np.concatenate([loop, inner])
    else:
        A, rows = A_b, loop
    return rows, A.reshape(-1, 2 * nc)


@dataclass
class PatternParams:
    """The effective control points K and the precomputed affine maps to control points and to
    the 2D rest mesh (module docstring).

    pattern: the pattern at rest. mesh: its GarmentMesh. controls, symmetry: as detected.
    control_uv: uv index of each control point, (Nc,) int64.
    L_c (2 Nc, 2 Nk), b_c (2 Nc,) [m]; L_u (2 Nu, 2 Nk), b_u (2 Nu,) [m]: torch float64, on the
    CPU unless moved with :meth:`to`.
    """

    pattern: Pattern
    mesh: object
    controls: ControlPoints
    symmetry: Symmetry
    control_uv: np.ndarray
    L_c: "torch.Tensor"  # noqa: F821
    b_c: "torch.Tensor"  # noqa: F821
    L_u: "torch.Tensor"  # noqa: F821
    b_u: "torch.Tensor"  # noqa: F821

    @classmethod
    def build(
        cls,
        pattern: Pattern,
        mesh,
        *,
        symmetry: Symmetry | None = None,
        controls: ControlPoints | None = None,
    ):
        """Precompute the maps for ``pattern`` meshed as ``mesh`` (from ``mesh_pattern(pattern)``).

        symmetry: a :class:`Symmetry` to use (default: ``detect_symmetry(pattern)``); its control
            points must be those of ``pattern``.
        controls: control points (default: ``find_control_points(pattern)``).
        """
        import torch

        if controls is None:
            controls = find_control_points(pattern)
        if symmetry is None:
            symmetry = detect_symmetry(pattern, controls=controls)
        if symmetry.n_control != len(controls) or not np.allclose(symmetry.c0, controls.positions, atol=1e-9):
            raise PatternError(
                "the stored symmetry does not match the pattern's control points; detect it again"
            )
        control_uv = _control_uv_index(pattern, mesh, controls)
        Lc, bc = symmetry.rebuild_map()
        nu, nk = mesh.n_uv, symmetry.n_k
        Lu = np.zeros((2 * nu, 2 * nk))
        bu = np.zeros(2 * nu)
        for p in range(len(controls.panel_names)):
            rows, A = deformation_matrix(mesh, controls, control_uv, p)
            cidx = controls.of_panel(p)
            crow = np.stack([2 * cidx, 2 * cidx + 1], axis=1).reshape(-1)
            urow = np.stack([2 * rows, 2 * rows + 1], axis=1).reshape(-1)
            Lu[urow] = A @ Lc[crow]
            bu[urow] = A @ bc[crow]
        t = lambda a: torch.as_tensor(a, dtype=torch.float64)  # noqa: E731
        return cls(pattern.copy(), mesh, controls, symmetry, control_uv, t(Lc), t(bc), t(Lu), t(bu))

    def to(self, device) -> "PatternParams":
        """The parameters with their maps on ``device`` (itself when they are there already)."""
        import torch

        device = torch.device(device)
        if self.L_u.device == device or (device.type == self.L_u.device.type and device.index is None):
            return self
        return dataclasses.replace(
            self,
            L_c=self.L_c.to(device),
            b_c=self.b_c.to(device),
            L_u=self.L_u.to(device),
            b_u=self.b_u.to(device),
        )

    @property
    def K0(self) -> "torch.Tensor":  # noqa: F821
        """The rest effective control points [m], (Nk, 2) torch float64, on the maps' device."""
        import torch

        return torch.as_tensor(self.symmetry.k0(), dtype=torch.float64, device=self.L_u.device)

    @property
    def n_k(self) -> int:
        """Number of effective control points Nk."""
        return self.symmetry.n_k

    def _apply(self, L, b, K):
        L = L.to(device=K.device, dtype=K.dtype)
        b = b.to(device=K.device, dtype=K.dtype)
        return (L @ K.reshape(-1) + b).reshape(-1, 2)

    def control_points(self, K: "torch.Tensor") -> "torch.Tensor":  # noqa: F821
        """All control points [m], (Nc, 2), from K [m], (Nk, 2); differentiable, K's dtype/device."""
        return self._apply(self.L_c, self.b_c, K)

    def uv(self, K: "torch.Tensor") -> "torch.Tensor":  # noqa: F821
        """All 2D rest vertices [m], (Nu, 2), from K [m], (Nk, 2); differentiable, K's dtype/device."""
        return self._apply(self.L_u, self.b_u, K)

    def k_from_control_points(self, C) -> "torch.Tensor":  # noqa: F821
        """The K [m], (Nk, 2) torch float64, whose rebuilt control points are closest (least squares)
        to the wanted positions C [m], (Nc, 2), of all control points: an edit made on all control
        points projected onto the symmetric parameters. For C that already respects the symmetries
        this is K read off C (exact). Solved on the CPU (``gelsd`` has no CUDA kernel); K comes
        back on the maps' device."""
        import torch

        C = torch.as_tensor(C, dtype=torch.float64).cpu().reshape(-1)
        sol = torch.linalg.lstsq(self.L_c.cpu(), (C - self.b_c.cpu()).unsqueeze(1), driver="gelsd").solution
        return sol.reshape(-1, 2).to(self.L_c.device)

    def to_pattern(self, K) -> Pattern:
        """A copy of the pattern with its panel vertices moved to ``uv(K)`` [m] (K: (Nk, 2)).
        Bezier curvature is relative to its edge, so it follows; a circular arc's radius [m] is
        scaled with its chord."""
        import torch

        with torch.no_grad():
            uv = self.uv(torch.as_tensor(K, dtype=torch.float64)).cpu().numpy()
        out = self.pattern.copy()
        for name in self.mesh.panel_names:
            panel = out.panels[name]
            old = panel.vertices.copy()
            for i, e in enumerate(panel.edges):
                panel.vertices[e.start] = uv[self.mesh.edge_verts[(name, i)][0]]
            for e in panel.edges:
                if e.curvature is not None and e.curvature.kind == "circle":
                    c0 = np.linalg.norm(old[e.end] - old[e.start])
                    c1 = np.linalg.norm(panel.vertices[e.end] - panel.vertices[e.start])
                    e.curvature.params[0] = float(e.curvature.params[0]) * (c1 / c0 if c0 > 0 else 1.0)
        return out


def check_inverted(uv, faces_uv, *, min_quality: float = 0.0) -> np.ndarray:
    """Indices (k,) int64 of triangles that are inverted or degenerate: signed area <= 0, or
    height over longest edge (twice the signed area over the longest edge squared) at most
    ``min_quality`` [-].

    uv: 2D vertex positions [m], (Nu, 2), numpy or torch. faces_uv: (F, 3) int, numpy or torch,
    counter-clockwise at rest.
    """
    try:
        import torch

        if isinstance(uv, torch.Tensor):
            uv = uv.detach().cpu().numpy()
        if isinstance(faces_uv, torch.Tensor):
            faces_uv = faces_uv.cpu().numpy()
    except ImportError:  # pragma: no cover
        pass
    uv = np.asarray(uv, dtype=np.float64)
    f = np.asarray(faces_uv, dtype=np.int64)
    a, b, c = uv[f[:, 0]], uv[f[:, 1]], uv[f[:, 2]]
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    if min_quality > 0:
        e2 = np.stack([((b - a) ** 2).sum(1), ((c - b) ** 2).sum(1), ((a - c) ** 2).sum(1)], axis=1).max(
            axis=1
        )
        return np.flatnonzero(area2 <= min_quality * np.maximum(e2, 1e-300)).astype(np.int64)
    return np.flatnonzero(area2 <= 0).astype(np.int64)
