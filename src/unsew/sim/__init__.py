"""Differentiable cloth simulation (paper 3.4): implicit Euler drape with exact gradients.

Public names (one import path each):
``Material``, ``MATERIALS``, ``get_material`` (material.py); ``SimModel`` (model.py);
``SimState`` (state.py); ``Cloth``, ``DrapeSettings``, ``drape``, ``sew``, ``merge_sewn`` (drape.py);
``drape_static``, ``StaticInfo``, ``StaticSettings`` (static.py);
``sparse_solve``, ``SparsePattern`` (solve.py); ``SphereSDF``, ``PlaneSDF``, ``CapsuleSDF``
(sdf_analytic.py). Importing this package imports torch.
"""

from unsew.sim.drape import Cloth, DrapeSettings, drape, merge_sewn, sew
from unsew.sim.material import MATERIALS, Material, get_material
from unsew.sim.model import SimModel
from unsew.sim.sdf_analytic import CapsuleSDF, PlaneSDF, SphereSDF
from unsew.sim.solve import SparsePattern, sparse_solve
from unsew.sim.state import SimState
from unsew.sim.static import StaticInfo, StaticSettings, drape_static

__all__ = [
    "Material",
    "MATERIALS",
    "get_material",
    "SimModel",
    "SimState",
    "Cloth",
    "DrapeSettings",
    "drape",
    "sew",
    "merge_sewn",
    "drape_static",
    "StaticInfo",
    "StaticSettings",
    "sparse_solve",
    "SparsePattern",
    "SphereSDF",
    "PlaneSDF",
    "CapsuleSDF",
]
