"""Cloth materials: the paper's Gamma = (H00, H01, H11, H22, k) plus density and friction.

Units (SI, per unit of cloth width/area, shell quantities):

- ``h00, h01, h11, h22`` [N/m]: entries of the linear orthotropic stiffness H of paper eq. 2,
  sigma = H eps with sigma the membrane (second Piola-Kirchhoff) stress per unit width [N/m]
  and eps = (E_uu, E_vv, 2 E_uv) the Green strain with *engineering* shear (see
  ``energies/membrane.py``). u is the warp (pattern x) direction, v the weft (pattern y).
- ``bend`` [N*m]: bending rigidity D (moment per unit width per unit curvature), as a lab
  measures it (KES-FB2 B, the cantilever's G = w g c^3); no value here is scaled for the mesh.
  The discrete energy of ``energies/bending.py`` stores D/2 * kappa^2 per unit area for a sheet
  bent uniformly along a grid's edges, and somewhat more on the panel mesher's meshes (its
  "Calibration", an option, removes the factor: docs/decisions/026-bending-calibration.md).
- ``density`` [kg/m^2]: areal density.
- ``friction``: Coulomb friction coefficient against the body (dimensionless).

Sources and conversions (representative values, not one measured sample each):

- Areal densities: fabric weights as sold. 1 oz/yd^2 = 33.906 g/m^2 (so 11 oz denim
  = 0.373 kg/m^2); shirting cotton 100-140 g/m^2, silk charmeuse/habotai 50-80 g/m^2, polyester
  plain weave ~100 g/m^2, cotton jersey 150-200 g/m^2, wool suiting 200-280 g/m^2.
- Bending rigidity: Kawabata Evaluation System (KES-FB2) bending rigidity B, reported in
  gf*cm^2/cm. Conversion: 1 gf*cm^2/cm = 9.80665e-3 N * 1e-4 m^2 / 1e-2 m = 9.80665e-5 N*m.
  Typical B (Kawabata 1980; Wang, O'Brien, Ramamoorthi 2011 "Data-driven elastic models for
  cloth" report bending of the same order for their 10 fabrics): silk 0.01-0.03, shirting
  cotton 0.04-0.1, polyester 0.03-0.08, jersey 0.02-0.05, wool suiting 0.08-0.15, denim 0.2-0.5.
- Tensile stiffness: small-strain slope of KES-FB1 / Wang et al. 2011 stretch curves, in N/m
  (force per unit width per unit strain): woven fabrics 1e3-1e4 N/m along the yarns (denim at
  the top, silk at the bottom), knits 1e2-1e3 N/m; shear (H22) one to two orders lower than
  the yarn directions for wovens; H01 = nu * sqrt(H00 H11) with a small Poisson ratio (0.1-0.3).
  Wang et al.'s piecewise-linear curves stiffen with strain; we take the low-strain slope, which
  is what a drape at a few percent strain sees.
- Friction: cloth on skin 0.3-0.5 (Derler and Gerhardt 2012, "Tribology of skin"), silk lower.

These values are a sensible initial Gamma for the optimizer (paper 4.1: "initialized with a
material set selected by the user from the material library"), not calibrated data.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from unsew.errors import InputError

__all__ = ["Material", "MATERIALS", "get_material", "check_gamma"]

#: 1 gf*cm^2/cm in N*m (KES bending rigidity unit).
_KES_B = 9.80665e-5


@dataclass(frozen=True)
class Material:
    """A cloth material.

    Attributes:
        h00: warp (u) tensile stiffness H00 [N/m].
        h01: coupling H01 [N/m].
        h11: weft (v) tensile stiffness H11 [N/m].
        h22: shear stiffness H22 [N/m] (engineering shear strain 2E_uv).
        bend: bending rigidity D [N*m].
        density: areal density [kg/m^2].
        friction: Coulomb friction coefficient with the body [-].
    """

    h00: float
    h01: float
    h11: float
    h22: float
    bend: float
    density: float
    friction: float = 0.3

    def __post_init__(self):
        check_gamma((self.h00, self.h01, self.h11, self.h22, self.bend))
        if not (self.density > 0 and math.isfinite(self.density)):
            raise InputError(f"material density must be positive [kg/m^2], got {self.density}")
        if not (self.friction >= 0 and math.isfinite(self.friction)):
            raise InputError(f"material friction must be >= 0, got {self.friction}")

    def gamma(self, *, dtype=None, device=None):
        """The paper's Gamma as a torch tensor (5,) = (H00, H01, H11, H22 [N/m], k [N*m]), float64."""
        import torch

        return torch.tensor(
            [self.h00, self.h01, self.h11, self.h22, self.bend],
            dtype=dtype or torch.float64,
            device=device,
        )


#: Keys of a material as written in material.json and in pattern.json's ``unsew.material`` (SI units).
MATERIAL_KEYS = (
    "H00_N_per_m",
    "H01_N_per_m",
    "H11_N_per_m",
    "H22_N_per_m",
    "bending_N_m",
    "density_kg_per_m2",
    "friction",
)


def material_to_dict(m: Material) -> dict:
    """A material as a JSON-ready dict: H00-H22 [N/m], bending [N*m], density [kg/m^2], friction [-]
    under :data:`MATERIAL_KEYS`."""
    return dict(zip(MATERIAL_KEYS, (m.h00, m.h01, m.h11, m.h22, m.bend, m.density, m.friction)))


def material_from_dict(d) -> Material:
    """The Material a :func:`material_to_dict` dict describes (material.json, or the
    ``unsew.material`` block of a fitted pattern.json). Raises InputError naming a missing or
    non-numeric key, or a stiffness that is not valid (:func:`check_gamma`)."""
    if not isinstance(d, dict):
        raise InputError(f"a material must be a JSON object with keys {', '.join(MATERIAL_KEYS)}")
    try:
        vals = [float(d[k]) for k in MATERIAL_KEYS]
    except KeyError as exc:
        raise InputError(f"material lacks {exc.args[0]!r} (needs {', '.join(MATERIAL_KEYS)})") from None
    except (TypeError, ValueError):
        raise InputError(f"material values must be numbers, got {d!r}") from None
    return Material(*vals)


def check_gamma(g) -> None:
    """Raise InputError unless Gamma (5,) = (H00, H01, H11, H22 [N/m], k [N*m]) gives a
    positive definite membrane stiffness and a non-negative bending stiffness."""
    h00, h01, h11, h22, k = (float(t) for t in g)
    vals = (h00, h01, h11, h22, k)
    if not all(math.isfinite(t) for t in vals):
        raise InputError(f"material parameters must be finite, got {vals}")
    if h00 <= 0 or h11 <= 0 or h22 <= 0:
        raise InputError(
            f"material stiffness must be positive (H00={h00:g}, H11={h11:g}, H22={h22:g} N/m); "
            "use values from unsew.sim.MATERIALS"
        )
    if h01 * h01 >= h00 * h11:
        raise InputError(
            f"material stiffness matrix not positive definite: H01^2={h01 * h01:g} >= H00*H11={h00 * h11:g}; "
            "lower |H01|"
        )
    if k < 0:
        raise InputError(f"bending stiffness must be >= 0 [N*m], got {k:g}")


def _woven(stretch, shear_frac, nu, bend_kes, density, friction):
    return Material(
        h00=stretch,
        h01=nu * stretch,
        h11=stretch,
        h22=shear_frac * stretch,
        bend=bend_kes * _KES_B,
        density=density,
        friction=friction,
    )


#: Material library (name -> Material). See the module docstring for sources and conversions.
MATERIALS: dict[str, Material] = {
    # shirting cotton, ~120 g/m^2, KES B ~0.06 gf cm^2/cm
    "cotton": _woven(3000.0, 0.05, 0.2, 0.06, 0.12, 0.35),
    # 11 oz/yd^2 denim = 0.373 kg/m^2, KES B ~0.3
    "denim": _woven(8000.0, 0.05, 0.2, 0.3, 0.373, 0.4),
    # silk, ~65 g/m^2, KES B ~0.02, slippery
    "silk": _woven(1500.0, 0.04, 0.2, 0.02, 0.065, 0.2),
    # polyester plain weave ~100 g/m^2, KES B ~0.05
    "polyester": _woven(4000.0, 0.05, 0.2, 0.05, 0.10, 0.3),
    # cotton jersey knit ~180 g/m^2: soft, weft (v) softer than wale, KES B ~0.03
    "jersey": Material(
        h00=600.0, h01=60.0, h11=300.0, h22=100.0, bend=0.03 * _KES_B, density=0.18, friction=0.45
    ),
    # wool suiting ~250 g/m^2, KES B ~0.1
    "wool": _woven(2500.0, 0.06, 0.25, 0.1, 0.25, 0.4),
}
MATERIALS["knit"] = MATERIALS["jersey"]


def get_material(name: str) -> Material:
    """Look up a material by name; InputError listing the known names otherwise."""
    try:
        return MATERIALS[name]
    except KeyError:
        raise InputError(f"unknown material {name!r}; choose one of {', '.join(sorted(MATERIALS))}") from None
