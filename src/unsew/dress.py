"""Dress a body with a sewing pattern: mesh the panels, place them around the body, sew the
seams shut (no gradients), and let the garment settle. The result is the first draped state
X of the paper (3.4.1) from which differentiable drapes are warm-started.

This is the one place the stages meet for a forward drape; the CLI's ``drape``, grading,
the fit and the benchmarks all call :func:`dress`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["Dressed", "dress", "resolve_material"]


@dataclass
class Dressed:
    """A pattern sewn and draped on a body.

    pattern: the Pattern; mesh: its GarmentMesh (uv (Nu,2) [m], faces (F,3) into X, ...);
    model: SimModel on the sewn topology; x: draped sewn vertices (Nx, 3) float64 torch [m];
    uv: rest positions (Nu, 2) float64 torch [m]; material: the Material used; sdf: the body SDF.
    """

    pattern: object
    mesh: object
    model: object
    x: object
    uv: object
    material: object
    sdf: object


def resolve_material(material):
    """A Material from a library name or a Material instance."""
    from unsew.sim.material import Material, get_material

    if isinstance(material, Material):
        return material
    return get_material(str(material))


def dress(
    pattern,
    body,
    *,
    sdf=None,
    mesh=None,
    edge_length: float = 0.025,
    material="cotton",
    gamma=None,
    sew_steps: int = 80,
    settle_steps: int = 40,
    dt: float = 0.05,
    progress: Callable[[str, int, int], None] | None = None,
) -> Dressed:
    """Mesh, place, sew and settle ``pattern`` on ``body``.

    Args:
        pattern: unsew.pattern.model.Pattern. body: unsew.body.body.Body.
        sdf: the body's SDF (built and disk-cached from ``body`` when None).
        mesh: a GarmentMesh of ``pattern`` to reuse (meshed at ``edge_length`` when None).
        edge_length: target triangle edge length [m].
        material: library name or Material; gamma: optional (5,) torch overriding its stiffness.
        sew_steps: steps of the sewing phase; settle_steps: steps of plain draping after it.
        dt: time step of the settle drape [s].
        progress: optional callback ``progress(phase, k, n)``.

    Returns:
        :class:`Dressed`.
    """
    import torch

    from unsew.body.placement import place_garment
    from unsew.meshing import mesh_pattern
    from unsew.sim.drape import drape, merge_sewn, sew
    from unsew.sim.model import SimModel
    from unsew.sim.state import SimState

    mat = resolve_material(material)
    if mesh is None:
        mesh = mesh_pattern(pattern, edge_length=edge_length)
    if sdf is None:
        from unsew.body.sdf import BodySDF

        sdf = BodySDF.build(body)
    g = mat.gamma() if gamma is None else torch.as_tensor(gamma, dtype=torch.float64).detach()
    uv = torch.as_tensor(np.asarray(mesh.uv), dtype=torch.float64)

    x_unsewn = place_garment(pattern, mesh, body)
    model_unsewn = SimModel.build(mesh.faces_uv, mesh.faces_uv, springs=mesh.seam_pairs)
    cb = (lambda k, s: progress("sew", k + 1, sew_steps)) if progress else None
    xs = sew(model_unsewn, x_unsewn, sdf, uv=uv, gamma=g, density=mat.density, steps=sew_steps,
             friction=mat.friction, callback=cb)
    x = merge_sewn(xs, mesh.x_of_u, mesh.n_x)
    model = SimModel.build(mesh.faces, mesh.faces_uv)
    if settle_steps > 0:
        cb = (lambda k, s: progress("settle", k + 1, settle_steps)) if progress else None
        with torch.no_grad():
            st = drape(model, SimState.at_rest(x), sdf, uv=uv, gamma=g, density=mat.density,
                       steps=settle_steps, dt=dt, friction=mat.friction, callback=cb)
        x = st.x
    return Dressed(pattern, mesh, model, x.detach(), uv, mat, sdf)
