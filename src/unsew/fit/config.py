"""Configuration of a fit: one frozen dataclass, every field with its unit, read from and
written to YAML so a result folder holds everything needed to rerun it (STYLE.md habit 13).

Defaults follow the paper (4.1): Adam with learning rate 1e-3, betas (0.9, 0.999),
lambda_open 0.1, lambda_mat 0.01, dt 0.05 s, 10-20 steps per drape; except lambda_seam, which is
1.0 here instead of the paper's 0.01, and the starting material, which the paper has the user
pick from the library and ``material: auto`` picks by draping (on bench_fit's skirt, in wool, a
fit from cotton ended 4.54 mm from its target and one from auto 2.36 mm). Our Chamfer term is a
mean of squared distances [m^2] and the seam term a sum of squared edge-length differences [m^2]
over all seam edges; with 0.01 the seam term had no effect: on the demo case the seam loss rose from 5e-7 to 1e-4 during the fit
(stitched edges drifting apart), while with 1.0 it stayed at 6e-6 and the fit reached a lower
Chamfer (2.9 mm against 4.6 mm). The paper does not state its loss scaling.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, fields
from pathlib import Path

from unsew.errors import InputError

__all__ = ["FitConfig", "load_config", "config_to_dict", "material_mask", "material_candidates"]


@dataclass(frozen=True)
class FitConfig:
    """Everything a fit needs besides its case folder.

    Units in brackets; [-] is dimensionless.
    """

    # pattern and meshing
    base: str = ""  #: base pattern: garment name or a GarmentCode JSON path; "" = meta.json's garment
    edge_length: float = 0.025  #: target triangle edge length of the panel meshes [m]
    material: str = "auto"  #: starting material: a library name (unsew.sim.material.MATERIALS; the paper's user choice), or "auto": grade in cotton, dress the graded pattern in each of `material_candidates`, grade again in the `material_regrade` best others, scale the winner's stiffness (`material_refine`), and start phase two from the drape closest to the target (mean surface distance)
    material_candidates: str = ""  #: comma list of library materials "auto" tries ("" = every material in the library)
    material_regrade: int = 2  #: "auto": how many of the best candidates other than cotton are graded again in their own fabric [-]
    material_refine: int = 2  #: "auto": rounds of the stiffness search after the choice (stretch and bending scaled by 1/s and s, s = 2, sqrt 2, ...; each kept when the drape comes closer); 0: off [-]

    # simulation
    dt: float = 0.05  #: time step [s]
    steps: int = 15  #: implicit Euler steps per differentiable drape [-]
    warm_start: bool = True  #: start each drape from the previous iteration's (the paper); False: always from the graded pattern's settled drape, so the drape depends on K and Gamma alone
    fit_friction_eps: float = 1e-2  #: slip speed below which friction is viscous in phase two's drapes [m/s] (the simulator's default; 1e-3 holds a warm-started drape from creeping down the body, docs/benchmarks.md "Where phase two's pattern drift comes from")
    sew_steps: int = 80  #: steps of the non-differentiated sewing phase [-]
    settle_steps: int = 40  #: steps of plain draping after sewing, before the first loss [-]

    # phase one: grading
    grading: bool = True  #: run linear grading before the optimization (ablation: False)

    # phase two: optimization
    iterations: int = 100  #: iteration budget of the optimization [-]
    lr: float = 1e-3  #: Adam learning rate for the control points [m per step]
    lr_decay: float = 1.0  #: factor the learning rates fall to, geometrically, over `iterations` [-] (1 = constant)
    lr_material: float = 5e-2  #: Adam learning rate for log-material parameters [-]
    betas: tuple[float, float] = (0.9, 0.999)  #: Adam betas [-]
    material_start: int = 20  #: iteration at which the material joins the variables [-]
    pattern_start: int = 0  #: iteration at which the control points K start to move [-] (0: from the first)
    optimize_material: bool = True  #: optimize Gamma = (H00, H01, H11, H22, k) (ablation: False)
    material_params: str = "H00,H01,H11,H22,k"  #: which entries of Gamma the material fit moves (comma list; the others keep the start material's value, H01 its ratio to sqrt(H00 H11))
    curvature_weighted: bool = True  #: curvature-weighted Chamfer, eq. 7 (ablation: plain Chamfer)
    lambda_open: float = 0.1  #: weight of the open-contour Chamfer, eq. 6 [-]
    lambda_seam: float = 1.0  #: weight of the seam-length loss, eq. 8 [-] (paper: 0.01; see module docstring)
    lambda_mat: float = 0.01  #: weight of the material range penalty [-]
    redress_check: bool = True  #: after phase two, dress the fitted pattern from scratch on the same mesh; if it lies no closer to the target (mean surface distance) than the graded pattern's drape, return the graded pattern and its drape (not in the paper)
    mesh_spread: float = 0.04  #: after the fit, dress the returned pattern from scratch on meshes of edge length x (1 - mesh_spread) and x (1 + mesh_spread); their distance to the target (metrics.json ``mesh_spread``) is how far the triangulation alone moves the drape (0: skip) [-]
    lambda_prior: float = 0.0  #: weight of the pull towards the start (graded) pattern: mean squared 2D rest-vertex move [m^2] (0: off, the paper's loss) [-]
    seam_loss: bool = True  #: include the seam loss (ablation: False)
    tol: float = 1e-3  #: stop when the loss changed by less than this fraction over `patience` iterations [-]
    patience: int = 15  #: iterations over which convergence is judged [-]
    target_points: int = 8000  #: target vertices kept for the Chamfer (random subset, seeded) [-]
    seed: int = 0  #: seed of every random choice [-]

    # outputs
    device: str = "cpu"  #: torch device for the simulation ("cpu", "cuda")
    report: bool = True  #: write report.html and its figures

    @property
    def drape(self):
        """The :class:`~unsew.sim.drape.DrapeSettings` of every drape of the fit."""
        from unsew.sim.drape import DrapeSettings

        return DrapeSettings(edge_length=self.edge_length, dt=self.dt, steps=self.steps, sew_steps=self.sew_steps,
                             settle_steps=self.settle_steps)

    def replace(self, **changes) -> "FitConfig":
        return dataclasses.replace(self, **changes)


def config_to_dict(cfg: FitConfig) -> dict:
    """Plain dict (YAML-ready) of a config."""
    d = dataclasses.asdict(cfg)
    d["betas"] = list(d["betas"])
    return d


def load_config(path: str | Path | None = None, *, defaults: dict | None = None, **overrides) -> FitConfig:
    """Read a YAML config and apply keyword overrides (None values are ignored).

    Precedence: overrides > the file > ``defaults`` > FitConfig's own defaults. Unknown keys and
    values of the wrong type raise InputError naming the key.
    """
    import yaml

    data: dict = dict(defaults or {})
    if path is not None:
        p = Path(path)
        if not p.is_file():
            raise InputError(f"config file {p} does not exist")
        try:
            loaded = yaml.safe_load(p.read_text()) or {}
        except yaml.YAMLError as exc:
            raise InputError(f"config file {p} is not valid YAML: {exc}".splitlines()[0]) from None
        if not isinstance(loaded, dict):
            raise InputError(f"config file {p} must hold a mapping of option: value")
        data.update(loaded)
    data.update({k: v for k, v in overrides.items() if v is not None})
    known = {f.name: f for f in fields(FitConfig)}
    unknown = sorted(set(data) - set(known))
    if unknown:
        raise InputError(f"unknown config option(s) {unknown}; known: {sorted(known)}")
    default = FitConfig()
    clean = {}
    for k, v in data.items():
        ref = getattr(default, k)
        try:
            if isinstance(ref, bool):
                if not isinstance(v, bool):
                    raise TypeError
                clean[k] = v
            elif isinstance(ref, int):
                if isinstance(v, bool) or int(v) != float(v):
                    raise TypeError
                clean[k] = int(v)
            elif isinstance(ref, float):
                clean[k] = float(v)
            elif isinstance(ref, tuple):
                clean[k] = tuple(float(x) for x in v)
                if len(clean[k]) != len(ref):
                    raise TypeError
            else:
                clean[k] = str(v)
        except (TypeError, ValueError):
            raise InputError(f"config option {k!r} must be like {ref!r}, got {v!r}") from None
    cfg = default.replace(**clean)
    _check(cfg)
    return cfg


def _check(cfg: FitConfig) -> None:
    if not 0.005 <= cfg.edge_length <= 0.1:
        raise InputError(f"edge_length {cfg.edge_length} m is outside 0.005-0.1 m")
    if cfg.dt <= 0 or cfg.dt > 0.2:
        raise InputError(f"dt {cfg.dt} s must be in (0, 0.2]")
    if not cfg.fit_friction_eps > 0:
        raise InputError(f"fit_friction_eps must be positive, got {cfg.fit_friction_eps} m/s")
    if not 0 <= cfg.mesh_spread < 0.5:
        raise InputError(f"mesh_spread must be in [0, 0.5), got {cfg.mesh_spread}")
    if cfg.material_refine < 0:
        raise InputError(f"material_refine must be >= 0, got {cfg.material_refine}")
    if cfg.material_regrade < 0:
        raise InputError(f"material_regrade must be >= 0, got {cfg.material_regrade}")
    for k in ("steps", "iterations", "target_points"):
        if getattr(cfg, k) < 1:
            raise InputError(f"{k} must be at least 1")
    if cfg.lr <= 0 or cfg.lr_material <= 0:
        raise InputError("learning rates must be positive")
    if not 0 < cfg.lr_decay <= 1:
        raise InputError(f"lr_decay {cfg.lr_decay} must be in (0, 1]")
    material_mask(cfg.material_params)
    if cfg.material != "auto":
        from unsew.sim.material import get_material

        get_material(cfg.material)  # InputError naming the library's materials
    material_candidates(cfg.material_candidates)


def material_candidates(spec: str) -> tuple[str, ...]:
    """The library materials ``material: auto`` tries: the comma list ``spec`` or, when empty,
    every distinct material of the library (aliases dropped). Raises InputError on an unknown name."""
    from unsew.sim.material import MATERIALS, get_material

    names = [n.strip() for n in str(spec).split(",") if n.strip()]
    if not names:
        seen, names = set(), []
        for n, m in MATERIALS.items():
            if id(m) not in seen:
                seen.add(id(m))
                names.append(n)
    for n in names:
        get_material(n)
    return tuple(dict.fromkeys(names))


#: Names of the entries of Gamma, in order (unsew.sim.material.Material.gamma()).
GAMMA_NAMES = ("H00", "H01", "H11", "H22", "k")


def material_mask(spec: str) -> tuple[bool, ...]:
    """Which entries of Gamma a ``material_params`` list (e.g. ``"H22,k"``) frees, in GAMMA_NAMES
    order. Raises InputError on an unknown or empty list."""
    names = [n.strip() for n in str(spec).split(",") if n.strip()]
    bad = sorted(set(names) - set(GAMMA_NAMES))
    if bad or not names:
        raise InputError(f"material_params {spec!r} must be a comma list of {', '.join(GAMMA_NAMES)}")
    return tuple(n in names for n in GAMMA_NAMES)
