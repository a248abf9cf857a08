"""Static simulation data: topology, hinge quads, sparsity pattern and index maps (paper 3.4.3).

Everything here is built once per topology with numpy and stored as torch tensors; a step only
gathers and scatters with these fixed indices (``index_add_``), never loops over elements and
never coalesces a sparse matrix.

The linear system is (3N x 3N), symmetric; we store its LOWER triangle (row >= col) as a COO
list ``rows, cols`` (int32 for cholespy, sorted by row then column) and one value per entry.
Each element block (triangle 9x9, hinge 12x12, spring 6x6, vertex 3x3) has a map from its flat
entries that fall in the lower triangle (``*_src``) to positions in the value array (``*_dst``).
Because element blocks are symmetric, dropping their upper part loses nothing.

Bending stencil. A hinge's 12x12 Gauss-Newton block 2c g g^T couples the two vertices opposite
its edge (x2, x3), which are not joined by a mesh edge. Those entries widen the sparsity graph
from the mesh's 1-ring to the "diamond" stencil, and the Cholesky fill and numeric factorization
time grow several-fold (``python -m benchmarks sim``). With ``bending_stencil="ring"``
(the default) the (x2, x3) blocks are left out of the pattern and the system uses instead

    2c (g g^T + P2 + P3),   P2 = g2 g2^T on block (2, 2), P3 = g3 g3^T on block (3, 3),

without the (2, 3) and (3, 2) blocks. The difference to the full block is 2c (g2; -g3)(g2; -g3)^T
on the (2, 3) corners, PSD, so the ring block dominates the full one (never less stiff: the
implicit step stays stable) and is itself PSD. Forces are unchanged (so are equilibria); only the
approximate Jacobian of the implicit step differs. ``"full"`` keeps the exact Gauss-Newton block.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import torch

from unsew.errors import InputError

__all__ = ["SimModel", "build_hinges", "BENDING_STENCILS"]

BENDING_STENCILS = ("ring", "full")


def build_hinges(faces: np.ndarray, faces_uv: np.ndarray):
    """Hinge quads of interior edges (edges shared by exactly two faces).

    Args:
        faces: (F, 3) int triangles into sim vertices.
        faces_uv: (F, 3) int the same triangles into rest (uv) vertices.

    Returns:
        hinges: (H, 4) int64 sim vertices (x0, x1, x2, x3); x0 -> x1 is the shared edge as
            ordered in the first face, x2 the first face's opposite vertex, x3 the second's.
        hinge_faces: (H, 2) int64 the two faces.
        hinge_uv_edges: (H, 4) int64 uv indices of the edge's end points in face 1 (2) and face 2 (2).
        n_nonmanifold: number of edges with more than two faces (skipped).
    """
    F = faces.shape[0]
    slot_a = np.array([0, 1, 2])
    slot_b = np.array([1, 2, 0])
    slot_o = np.array([2, 0, 1])
    e0 = faces[:, slot_a].reshape(-1)  # (3F,) edge start
    e1 = faces[:, slot_b].reshape(-1)
    fid = np.repeat(np.arange(F), 3)
    slot = np.tile(np.arange(3), F)
    lo, hi = np.minimum(e0, e1), np.maximum(e0, e1)
    key = lo.astype(np.int64) * (int(faces.max(initial=0)) + 1) + hi
    order = np.argsort(key, kind="stable")
    ks = key[order]
    uniq, start, counts = np.unique(ks, return_index=True, return_counts=True)
    two = counts == 2
    ia = order[start[two]]
    ib = order[start[two] + 1]
    fa, fb = fid[ia], fid[ib]
    sa, sb = slot[ia], slot[ib]
    x0 = faces[fa, slot_a[sa]]
    x1 = faces[fa, slot_b[sa]]
    x2 = faces[fa, slot_o[sa]]
    x3 = faces[fb, slot_o[sb]]
    hinges = np.stack([x0, x1, x2, x3], 1).astype(np.int64)
    hinge_faces = np.stack([fa, fb], 1).astype(np.int64)
    uv_e = np.stack(
        [
            faces_uv[fa, slot_a[sa]],
            faces_uv[fa, slot_b[sa]],
            faces_uv[fb, slot_a[sb]],
            faces_uv[fb, slot_b[sb]],
        ],
        1,
    ).astype(np.int64)
    return hinges, hinge_faces, uv_e, int((counts > 2).sum())


def _block_entries(elems: np.ndarray):
    """Global scalar (row, col) of every entry of each element's (3k x 3k) block, flattened.

    elems: (E, k) vertex indices. Returns rows, cols: (E*9k^2,) int64."""
    E, k = elems.shape
    dof = (3 * elems[:, :, None] + np.arange(3)[None, None, :]).reshape(E, 3 * k)  # (E, 3k)
    rows = np.broadcast_to(dof[:, :, None], (E, 3 * k, 3 * k)).reshape(-1)
    cols = np.broadcast_to(dof[:, None, :], (E, 3 * k, 3 * k)).reshape(-1)
    return rows, cols


def _as_numpy(a) -> np.ndarray:
    return np.asarray(a.detach().cpu() if torch.is_tensor(a) else a)


def _check_faces(faces, faces_uv, n, n_rest):
    """Validated (F, 3) int64 ``faces`` and ``faces_uv`` with their vertex counts (N, Nu)."""
    faces, faces_uv = _as_numpy(faces), _as_numpy(faces_uv)
    if faces.ndim != 2 or faces.shape[1] != 3 or faces.shape[0] == 0:
        raise InputError(f"faces must be a non-empty (F, 3) integer array, got shape {faces.shape}")
    if faces_uv.shape != faces.shape:
        raise InputError(f"faces_uv {faces_uv.shape} must have the same shape as faces {faces.shape}")
    faces = faces.astype(np.int64)
    faces_uv = faces_uv.astype(np.int64)
    if faces.min() < 0 or faces_uv.min() < 0:
        raise InputError("faces and faces_uv must hold non-negative vertex indices")
    n = int(faces.max()) + 1 if n is None else int(n)
    n_rest = int(faces_uv.max()) + 1 if n_rest is None else int(n_rest)
    if faces.max() >= n or faces_uv.max() >= n_rest:
        raise InputError(f"face indices out of range (N={n}, Nu={n_rest})")
    if np.any((faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])):
        raise InputError("faces repeat a vertex within a triangle; remove degenerate faces")
    return faces, faces_uv, n, n_rest


def _check_springs(springs, n: int) -> np.ndarray:
    """(S, 2) int64 springs within range, self-springs dropped; None gives (0, 2)."""
    if springs is None:
        return np.zeros((0, 2), np.int64)
    springs = _as_numpy(springs).astype(np.int64).reshape(-1, 2)
    if springs.size and (springs.min() < 0 or springs.max() >= n):
        raise InputError(f"springs index vertices out of range (N={n})")
    return springs[springs[:, 0] != springs[:, 1]]


def _pin_mask(pinned, n: int) -> np.ndarray:
    """(N,) bool mask from an (N,) bool mask, (P,) int indices or None."""
    pin = np.zeros(n, bool)
    if pinned is not None:
        p = _as_numpy(pinned)
        if p.dtype == bool:
            if p.shape != (n,):
                raise InputError(f"pinned mask must have shape ({n},), got {p.shape}")
            pin = p.copy()
        else:
            pin[p.astype(np.int64)] = True
    return pin


def _sparsity(groups: dict, n: int, bending_stencil: str):
    """Lower-triangle COO pattern of the (3N x 3N) system and the index maps into it.

    groups: element arrays by name ("tri" (F, 3), "hinge" (H, 4), "spring" (S, 2), "vert" (N, 1)).
    Returns rows, cols: (nnz,) int32; diag_dst: (3N,) int64 value index of each diagonal entry;
    maps: name -> (src, dst) int64 tensors from the flat element blocks to the value array.
    """
    n3 = 3 * n
    per = {}
    for name, elems in groups.items():
        r, c = _block_entries(elems) if elems.shape[0] else (np.zeros(0, np.int64), np.zeros(0, np.int64))
        sel = r >= c
        if name == "hinge" and bending_stencil == "ring":
            local = np.arange(r.shape[0]) % 144
            ca, cb = local // 12 // 3, local % 12 // 3  # corners of the entry's row and column
            sel &= ~(((ca == 2) & (cb == 3)) | ((ca == 3) & (cb == 2)))
        lower = np.nonzero(sel)[0]
        per[name] = (lower, r[lower] * n3 + c[lower])
    keys = np.unique(np.concatenate([key for _, key in per.values()]))
    rows = (keys // n3).astype(np.int32)
    cols = (keys % n3).astype(np.int32)
    maps = {
        name: (torch.from_numpy(lower), torch.from_numpy(np.searchsorted(keys, key)))
        for name, (lower, key) in per.items()
    }
    diag = np.arange(n3, dtype=np.int64)
    diag_dst = np.searchsorted(keys, diag * n3 + diag)
    return rows, cols, diag_dst, maps


@dataclass
class SimModel:
    """Static topology of a cloth for simulation (built by :meth:`SimModel.build`).

    Attributes (torch tensors, all on one device: the CPU unless moved with :meth:`to`):
        n: number of sim vertices N.
        n_rest: number of rest (uv) vertices Nu.
        faces: (F, 3) int64 into sim vertices.
        faces_uv: (F, 3) int64 into rest vertices.
        hinges: (H, 4) int64, hinge_faces (H, 2), hinge_uv_edges (H, 4) (see :func:`build_hinges`).
        springs: (S, 2) int64 zero-length springs between sim vertices (sewing phase).
        pinned: (N,) bool; pinned vertices keep their velocity (dv = 0).
        rows, cols: (nnz,) int32 lower-triangle COO pattern of the (3N x 3N) system.
        diag_dst: (3N,) int64 value index of each diagonal entry.
        tri_src/tri_dst, hinge_src/hinge_dst, spring_src/spring_dst, vert_src/vert_dst: int64
            index maps from flat element blocks to the value array.
        hinge_w: (len(hinge_src),) int64 the entry of the flat 12x12 hinge block each hinge_src
            entry reads (hinge_src % 144), where the "ring" stencil's corner weight is read.
        hinge_rows, hinge_cols: (len(hinge_src),) int64 the two factors of each hinge_src entry of
            the block s g g^T: its positions in the flat (H * 12,) arrays s g and g.
        keep: (nnz,) float64 0 on rows/cols of pinned dofs, 1 elsewhere.
        n_nonmanifold: interior edges skipped for bending (more than two faces).
        bending_stencil: "ring" (hinge blocks without the opposite-vertex coupling, see the
            module docstring) or "full".
    """

    n: int
    n_rest: int
    faces: torch.Tensor
    faces_uv: torch.Tensor
    hinges: torch.Tensor
    hinge_faces: torch.Tensor
    hinge_uv_edges: torch.Tensor
    springs: torch.Tensor
    pinned: torch.Tensor
    rows: torch.Tensor
    cols: torch.Tensor
    diag_dst: torch.Tensor
    tri_src: torch.Tensor
    tri_dst: torch.Tensor
    hinge_src: torch.Tensor
    hinge_dst: torch.Tensor
    hinge_w: torch.Tensor
    hinge_rows: torch.Tensor
    hinge_cols: torch.Tensor
    spring_src: torch.Tensor
    spring_dst: torch.Tensor
    vert_src: torch.Tensor
    vert_dst: torch.Tensor
    keep: torch.Tensor
    n_nonmanifold: int = 0
    bending_stencil: str = "full"

    @property
    def nnz(self) -> int:
        """Number of stored (lower-triangle) entries of the system matrix."""
        return int(self.rows.shape[0])

    @property
    def device(self) -> torch.device:
        """The device of the model's tensors (all on one)."""
        return self.faces.device

    def to(self, device) -> "SimModel":
        """The model with every tensor on ``device`` (itself when they are there already). The
        per-topology caches of the integrator (sparse pattern, adjoint maps) are rebuilt on the
        new device at first use."""
        device = torch.device(device)
        if self.device == device or (device.type == self.device.type and device.index is None):
            return self
        moved = {
            f.name: getattr(self, f.name).to(device)
            for f in dataclasses.fields(self)
            if torch.is_tensor(getattr(self, f.name))
        }
        return dataclasses.replace(self, **moved)

    @classmethod
    def build(
        cls,
        faces,
        faces_uv,
        *,
        springs=None,
        pinned=None,
        n: int | None = None,
        n_rest: int | None = None,
        bending_stencil: str = "ring",
    ):
        """Build the static model.

        Args:
            faces: (F, 3) int triangles into N sim vertices (sewn topology X).
            faces_uv: (F, 3) int the same triangles into Nu rest vertices (2D pattern U).
            springs: (S, 2) int pairs of sim vertices joined by zero-length springs (sewing), or None.
            pinned: (N,) bool mask or (P,) int indices of vertices whose velocity is held, or None.
            n: number of sim vertices (default faces.max() + 1).
            n_rest: number of rest vertices (default faces_uv.max() + 1).
            bending_stencil: "ring" (default: hinge blocks kept within the mesh's 1-ring,
                several times cheaper factorizations) or "full" (see the module docstring).

        Raises:
            InputError: empty or inconsistent faces, indices out of range.
        """
        if bending_stencil not in BENDING_STENCILS:
            raise InputError(f"bending_stencil must be one of {BENDING_STENCILS}, got {bending_stencil!r}")
        faces, faces_uv, n, n_rest = _check_faces(faces, faces_uv, n, n_rest)
        springs = _check_springs(springs, n)
        pin = _pin_mask(pinned, n)
        hinges, hinge_faces, hinge_uv, n_nm = build_hinges(faces, faces_uv)
        verts = np.arange(n, dtype=np.int64)[:, None]
        groups = {"tri": faces, "hinge": hinges, "spring": springs, "vert": verts}
        rows, cols, diag_dst, maps = _sparsity(groups, n, bending_stencil)
        free = ~np.repeat(pin, 3)
        keep = (free[rows] & free[cols]).astype(np.float64)

        t = torch.from_numpy
        return cls(
            n=n,
            n_rest=n_rest,
            faces=t(faces),
            faces_uv=t(faces_uv),
            hinges=t(hinges),
            hinge_faces=t(hinge_faces),
            hinge_uv_edges=t(hinge_uv),
            springs=t(springs),
            pinned=t(pin),
            rows=t(rows),
            cols=t(cols),
            diag_dst=t(diag_dst),
            **{f"{g}_{end}": maps[g][i] for g in groups for i, end in enumerate(("src", "dst"))},
            hinge_w=maps["hinge"][0] % 144,
            hinge_rows=maps["hinge"][0] // 12,
            hinge_cols=(maps["hinge"][0] // 144) * 12 + maps["hinge"][0] % 12,
            keep=t(keep),
            n_nonmanifold=n_nm,
            bending_stencil=bending_stencil,
        )
