"""The target garment as the fit sees it: its mesh, its open contours, and the distance a drape
lies from it (the mean surface Chamfer the metrics and the report use)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.body.skeleton import distance_to_bone
from unsew.geometry.repair import triangle_areas
from unsew.losses.contours import open_contours
from unsew.metrics.surface import surface_metrics

__all__ = ["Target", "OBJECTIVE_SAMPLES", "torso_band_faces"]

#: Surface samples per side of the distance that choices are made on (material, re-dress check).
OBJECTIVE_SAMPLES = 20_000


@dataclass
class Target:
    """The target mesh T.

    verts: (V, 3) float64 [m]; faces: (F, 3) int64; contours: its open contours (hems, cuffs,
    necklines; :func:`unsew.losses.contours.open_contours`); seed: of every sampling.
    """

    verts: np.ndarray
    faces: np.ndarray
    contours: list
    seed: int = 0

    @classmethod
    def of_case(cls, case, *, seed: int = 0) -> "Target":
        """The target of a loaded case (unsew.io.case.Case)."""
        tv = np.asarray(case.target_verts, dtype=np.float64)
        tf = np.asarray(case.target_faces, dtype=np.int64)
        return cls(tv, tf, open_contours(tv, tf), seed)

    @property
    def area(self) -> float:
        """The target's surface area A_T [m^2] (summed triangle areas)."""
        return float(triangle_areas(self.verts, self.faces).sum())

    def distance_mm(self, x, faces, *, n_samples: int = OBJECTIVE_SAMPLES) -> float:
        """Mean surface distance [mm] between the drape ``x`` (N, 3) [m] on ``faces`` and the target.

        Choices are made on this figure, not on the fit's squared loss, which tells fabrics apart
        far less (docs/decisions/002).
        """
        return surface_metrics(
            np.asarray(x), faces, self.verts, self.faces, n_samples=n_samples, seed=self.seed
        )["chamfer_mm"]

    def band_distance_mm(
        self, x, faces, skeleton, low: float, high: float, *, n_samples: int = OBJECTIVE_SAMPLES
    ) -> float:
        """:meth:`distance_mm` over the torso between heights ``low`` and ``high`` [m] only: both
        surfaces cut to :func:`torso_band_faces` (the drape ``x`` (N, 3) [m] on ``faces``, the
        body's ``skeleton``). NaN when either has no cloth there."""
        x, faces = np.asarray(x), np.asarray(faces)
        mine = torso_band_faces(x, faces, skeleton, low, high)
        theirs = torso_band_faces(self.verts, self.faces, skeleton, low, high)
        if not mine.any() or not theirs.any():
            return float("nan")
        return surface_metrics(
            x, faces[mine], self.verts, self.faces[theirs], n_samples=n_samples, seed=self.seed
        )["chamfer_mm"]


def torso_band_faces(verts, faces, skeleton, low: float, high: float) -> np.ndarray:
    """Faces (F,) bool of a surface (verts (V, 3) [m], faces (F, 3)) whose centroid lies between
    heights ``low`` and ``high`` [m] (Y up) and nearer a torso bone of ``skeleton`` than any
    other (a sleeve or an arm beside the waist is left out)."""
    c = np.asarray(verts)[np.asarray(faces)].mean(axis=1)
    keep = (c[:, 1] >= low) & (c[:, 1] <= high)
    bones = skeleton.bones()
    if not keep.any() or not bones:
        return keep
    d = np.stack([distance_to_bone(c[keep], b) for b in bones], axis=1)
    torso = np.array([b.part == "torso" for b in bones])
    keep[np.flatnonzero(keep)] = torso[d.argmin(axis=1)]
    return keep
