"""Configuration of a fit: frozen dataclasses, one per concern, every field with its unit, read
from and written to YAML so a result folder holds everything needed to rerun it (STYLE.md habit 13).

A config file groups its settings (``drape:``, ``material:``, ``optimizer:``, ``loss:``,
``checks:``, ``output:``); :func:`user_settings` lists them all (``unsew fit --help`` prints them,
with their defaults). Only what a user tunes is a setting: the rest are constants of the modules
that use them (a ``ClassVar`` of a group here where unsew.fit.optimize reads it through the group).
A key of the flat files of earlier versions (``iterations: 100``, ``sew_steps: 80``, ...) or a
former setting is refused with the name it has now, or the constant it became.

Defaults follow the paper (4.1): Adam with learning rate 1e-3, betas (0.9, 0.999),
lambda_open 0.1, lambda_mat 0.01, dt 0.05 s, 10-20 steps per drape; except the seam weight, 1.0
here instead of the paper's 0.01, and the starting material, which the paper has the user pick
from the library and ``material.start: auto`` picks by draping (docs/decisions/001 and 002).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import ClassVar

from unsew.errors import InputError

# how grading reads a waistband's target loop (``band_gap``)
from unsew.grading.band_gap import BAND_GAP_MODES
from unsew.sim.drape import DrapeSettings
from unsew.sim.material import MATERIALS, get_material

__all__ = [
    "FitConfig",
    "MaterialSettings",
    "OptimizerSettings",
    "LossWeights",
    "CheckSettings",
    "OutputSettings",
    "DRAPE_KEYS",
    "load_config",
    "config_to_dict",
    "user_settings",
    "material_mask",
    "material_candidates",
    "GAMMA_NAMES",
]

#: Names of the entries of Gamma, in order (unsew.sim.material.Material.gamma()).
GAMMA_NAMES = ("H00", "H01", "H11", "H22", "k")

#: The fields of :class:`~unsew.sim.drape.DrapeSettings` a fit's ``drape:`` group sets; the others
#: (sewing time step and springs, gravity, contact, solver) are the simulator's own defaults.
DRAPE_KEYS = ("edge_length", "dt", "steps", "sew_steps", "settle_steps")


@dataclass(frozen=True)
class MaterialSettings:
    """The fabric: where the fit starts and what phase two may change of it."""

    #: a library name (the paper's user choice), or "auto": the fabric whose drape of the graded pattern lies
    #: closest to the target, its stiffness then refined (docs/decisions/002)
    start: str = "auto"
    candidates: tuple[str, ...] = ()  #: library materials "auto" tries (empty: every material in the library)
    #: entries of Gamma phase two moves (the others keep the start's value, H01 its ratio to sqrt(H00 H11));
    #: empty: the material stays fixed
    fit: tuple[str, ...] = GAMMA_NAMES
    start_iteration: int = 20  #: iteration at which the material joins the variables [-]
    lr: float = 5e-2  #: Adam learning rate of the log-material parameters [-]


#: What the fit does with the target's surface area (``area``).
AREA_MODES = ("free", "target")

#: What grading does with the side seams (``side_seams``; unsew.grading.grade.SIDE_SEAM_MODES).
SIDE_SEAM_MODES = ("none", "girth")


@dataclass(frozen=True)
class OptimizerSettings:
    """Phase two's Adam loop. The class constants (not settings) are the loop's fixed parts."""

    iterations: int = 100  #: iteration budget [-]
    lr: float = 1e-3  #: Adam learning rate of the control points [m per step]
    pattern_start: int = 0  #: iteration at which the control points K start to move [-]

    betas: ClassVar[tuple[float, float]] = (0.9, 0.999)  #: Adam betas [-] (the paper's)
    #: factor the learning rates fall to, geometrically, over `iterations` [-] (1: constant, the paper's)
    lr_decay: ClassVar[float] = 1.0
    #: start each drape from the previous iteration's (the paper); False: always from the graded drape
    warm_start: ClassVar[bool] = True
    #: slip speed below which friction is viscous in phase two's drapes (only) [m/s]
    friction_eps: ClassVar[float] = 1e-2
    #: a control point of a panel narrower than this (area / half perimeter) moves by lr x width / panel_width
    #: per step (waistbands: 3.6 cm, x0.36); 0: every point at lr [m]
    panel_width: ClassVar[float] = 0.1
    #: what phase two may change of a waistband (a panel open only along its top): "free" anything, "height"
    #: its girth only, "held" nothing (docs/decisions/013)
    bands: ClassVar[str] = "free"
    #: stitched edge lengths: "soft" pulled by the seam loss; "held" put back in the graded ratio after every
    #: step; "trued" once, on the best iterate (unsew.pattern.seams; docs/decisions/013)
    seams: ClassVar[str] = "soft"
    tol: ClassVar[float] = 1e-3  #: stop when the loss changed by less than this fraction over `patience` [-]
    patience: ClassVar[int] = 15  #: iterations over which convergence is judged [-]
    #: > 0: phase two's control-point steps are line searched (a step raising the loss is retried at half
    #: length, at most this many times, else not taken; lr: the move of the point moving most;
    #: docs/decisions/018); 0: Adam's steps, every one kept (the paper) [-]
    retries: ClassVar[int] = 3
    #: > 0: phase two starts from a drape at rest, the graded drape draped on until its 99th-percentile vertex
    #: speed falls below this; 0: off (docs/decisions/013) [m/s]
    rest_speed: ClassVar[float] = 0.0
    rest_steps: ClassVar[int] = 160  #: most steps the graded drape is let settle before phase two [-]


@dataclass(frozen=True)
class LossWeights:
    """Weights of the loss terms (eqs. 5-9); a weight of 0 drops its term. The class constants
    (not settings) are terms measured and left off (docs/decisions/013) and the barrier's bound."""

    curvature_weighted: bool = True  #: curvature-weighted Chamfer, eq. 7 (ablation: plain Chamfer)
    open: float = 0.1  #: open-contour Chamfer, eq. 6 [-]
    seam: float = 1.0  #: seam-length loss, eq. 8 [-] (paper: 0.01; docs/decisions/001)
    material: float = 0.01  #: material range penalty [-]
    #: barrier against overstretched cloth, sum over drape edges of relu(stretch - stretch_bound)^2
    #: (unsew.losses.stretch; not in the paper; docs/decisions/006) [-]
    stretch: float = 1e-4
    target_points: int = 8000  #: target vertices kept for the Chamfer (random subset, seeded) [-]

    #: pull towards the graded pattern: mean squared 2D rest-vertex move [m^2] (0: the paper's loss) [-]
    prior: ClassVar[float] = 0.0
    #: pull of the pattern's total area towards the target's surface area, (A / A_T - 1)^2 (unsew.losses.area;
    #: 0: off, docs/decisions/013) [m^2]
    area: ClassVar[float] = 0.0
    #: pull of each panel's rest area towards its graded area, mean of (A_p / A_p0 - 1)^2
    #: (unsew.losses.panel_area; 0: off, docs/decisions/013) [-]
    panel_area: ClassVar[float] = 0.0
    stretch_bound: ClassVar[float] = (
        1.5  #: edge stretch (length over rest length) the barrier lets pass free [-]
    )


@dataclass(frozen=True)
class CheckSettings:
    """Checks after phase two (not in the paper)."""

    #: dress the fitted pattern from scratch; unless it lies closer to the target than the graded drape,
    #: return the graded pattern
    redress: bool = True
    #: dress the returned pattern on meshes of edge length x (1 -/+ mesh_spread) and report their distance to
    #: the target (0: skip) [-]
    mesh_spread: float = 0.04


@dataclass(frozen=True)
class OutputSettings:
    """What a fit writes besides the pattern, garment and metrics."""

    report: bool = True  #: write report.html and its figures


@dataclass(frozen=True)
class FitConfig:
    """Everything a fit needs besides its case folder. Units in brackets; [-] is dimensionless."""

    #: base pattern: a garment type or library base name (unsew.pattern.base.BASES), or a GarmentCode JSON
    #: path; "" = chosen by draping among the library's bases of meta.json's garment type
    base: str = ""
    grading: bool = True  #: run linear grading before the optimization (ablation: False)
    #: "target": grading scales each graded pattern to the target's surface area and phase two holds its total
    #: rest area (unsew.grading.area; docs/decisions/004); "free": the paper's fit
    area: str = "target"
    #: "girth": for a garment hanging from the shoulders, grading moves the side seams by the target's torso
    #: girth (unsew.grading.profile; docs/decisions/008); "none": the paper's Algorithm 2
    side_seams: str = "girth"
    #: "target": a garment hanging from its band (a skirt) gets its band sized to the target's top loop less
    #: the target's contact gap (unsew.grading.band_gap; docs/decisions/009); "none": the loop as measured
    band_gap: str = "target"
    seed: int = 0  #: seed of every random choice [-]
    device: str = "cpu"  #: torch device for the simulation ("cpu", "cuda")
    #: seconds the fit aims to end within, from the command's start; the material choice's optional steps,
    #: phase two's iterations, the three-mesh re-dress and the mesh spread give way (unsew.fit.budget); 0: no
    #: limit [s]
    time_limit: float = 540.0
    #: meshing, sewing, settling and drape steps: the fields DRAPE_KEYS are settings, the rest the simulator's
    drape: DrapeSettings = field(default_factory=DrapeSettings)
    material: MaterialSettings = field(default_factory=MaterialSettings)
    optimizer: OptimizerSettings = field(default_factory=OptimizerSettings)
    loss: LossWeights = field(default_factory=LossWeights)
    checks: CheckSettings = field(default_factory=CheckSettings)
    output: OutputSettings = field(default_factory=OutputSettings)

    def replace(self, **changes) -> "FitConfig":
        """A copy with ``changes`` applied: top-level fields or whole groups."""
        return dataclasses.replace(self, **changes)

    @property
    def fits_material(self) -> bool:
        """Whether phase two moves any entry of Gamma."""
        return bool(self.material.fit)


_GROUPS = {
    f.name: f.default_factory for f in fields(FitConfig) if f.default_factory is not dataclasses.MISSING
}
_STR_LISTS = {"material.candidates", "material.fit"}


def _group_keys(group: str) -> tuple[str, ...]:
    """The settings of a group: its dataclass fields (the drape's: DRAPE_KEYS)."""
    return DRAPE_KEYS if group == "drape" else tuple(f.name for f in fields(_GROUPS[group]))


def user_settings() -> dict:
    """Every setting a user sets, in the config's order: ``{"group.name" or "name": default}``
    (the top-level fields, then each group's; counted from the dataclasses' fields)."""
    cfg = FitConfig()
    out = {f.name: getattr(cfg, f.name) for f in fields(FitConfig) if f.name not in _GROUPS}
    for g in _GROUPS:
        out.update({f"{g}.{n}": getattr(getattr(cfg, g), n) for n in _group_keys(g)})
    return out


#: Names of the flat config files of earlier versions -> the setting's name now.
_RENAMED = {
    "edge_length": "drape.edge_length", "dt": "drape.dt", "steps": "drape.steps",
    "sew_steps": "drape.sew_steps", "settle_steps": "drape.settle_steps", "material": "material.start",
    "material_candidates": "material.candidates", "material_params": "material.fit",
    "material_start": "material.start_iteration", "lr_material": "material.lr",
    "iterations": "optimizer.iterations", "lr": "optimizer.lr", "pattern_start": "optimizer.pattern_start",
    "curvature_weighted": "loss.curvature_weighted", "lambda_open": "loss.open", "lambda_seam": "loss.seam",
    "lambda_mat": "loss.material", "target_points": "loss.target_points",
    "redress_check": "checks.redress", "mesh_spread": "checks.mesh_spread", "report": "output.report",
    "seam_loss": "loss.seam (0: off)", "optimize_material": "material.fit ([]: the material fixed)",
}  # fmt: skip
#: Former settings -> the constant each became.
_RETIRED = {
    "base_choice_edge": "unsew.fit.start.BASE_CHOICE_EDGE",
    "contact": "unsew.fit.contact.CONTACT",
    "material.regrade": "unsew.fit.material.REGRADE",
    "material.warm_steps": "unsew.fit.start.WARM_STEPS",
    "material.check": "unsew.fit.material.CHECK_CHOICE",
    "material.refine": "unsew.fit.material.REFINE_ROUNDS",
    "checks.redress_meshes": "unsew.fit.checks.REDRESS_MESHES",
    **{f"drape.{f.name}": f"unsew.sim.drape.DrapeSettings.{f.name}" for f in fields(DrapeSettings)
       if f.name not in DRAPE_KEYS},
    **{f"{g}.{n}": f"unsew.fit.config.{cls.__name__}.{n}" for g, cls in (("optimizer", OptimizerSettings),
       ("loss", LossWeights)) for n in cls.__annotations__ if n not in _group_keys(g)},
}  # fmt: skip
_RETIRED_FLAT = {
    "material_regrade": "material.regrade", "material_refine": "material.refine",
    "lr_decay": "optimizer.lr_decay", "betas": "optimizer.betas", "warm_start": "optimizer.warm_start",
    "fit_friction_eps": "optimizer.friction_eps", "tol": "optimizer.tol", "patience": "optimizer.patience",
    "lambda_prior": "loss.prior", "redress_meshes": "checks.redress_meshes",
}  # fmt: skip


def config_to_dict(cfg: FitConfig) -> dict:
    """Plain nested dict (YAML-ready: lists, not tuples) of a config's settings."""
    out = {f.name: getattr(cfg, f.name) for f in fields(FitConfig) if f.name not in _GROUPS}
    for g in _GROUPS:
        out[g] = {n: getattr(getattr(cfg, g), n) for n in _group_keys(g)}
    return _lists(out)


def _lists(v):
    if isinstance(v, dict):
        return {k: _lists(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_lists(x) for x in v]
    return v


def load_config(path: str | Path | None = None, *, defaults: dict | None = None, **overrides) -> FitConfig:
    """Read a YAML config and apply keyword overrides (None values are ignored).

    Precedence: overrides > the file > ``defaults`` > FitConfig's own defaults. Each source may
    be grouped (``{"optimizer": {"iterations": 9}}``) or dotted (``{"optimizer.iterations": 9}``).
    Unknown keys, keys of earlier versions (named with their place now) and values of the wrong
    type raise a one-line InputError naming the key.
    """
    flat: dict = {}
    for source in (
        defaults or {},
        _read_yaml(path) if path is not None else {},
        {k: v for k, v in overrides.items() if v is not None},
    ):
        _flatten(source, flat)
    groups: dict = {g: {} for g in _GROUPS}
    top: dict = {}
    for place, value in flat.items():
        g, _, name = place.partition(".")
        ref = getattr(FitConfig(), g) if name else FitConfig()
        value = _coerce(place, getattr(ref, name or g), value)
        (groups[g] if name else top)[name or g] = value
    cfg = FitConfig(**top, **{g: _GROUPS[g](**kw) for g, kw in groups.items()})
    _check(cfg)
    return cfg


def _read_yaml(path) -> dict:
    import yaml

    p = Path(path)
    if not p.is_file():
        raise InputError(f"config file {p} does not exist")
    try:
        loaded = yaml.safe_load(p.read_text()) or {}
    except yaml.YAMLError as exc:
        raise InputError(f"config file {p} is not valid YAML: {exc}".splitlines()[0]) from None
    if not isinstance(loaded, dict):
        raise InputError(f"config file {p} must hold a mapping of option: value")
    if isinstance(loaded.get("config"), dict) and "unsew_version" in loaded:
        loaded = loaded["config"]  # a result folder's config.yaml
    return loaded


def _flatten(source: dict, flat: dict) -> None:
    """Add ``source``'s settings to ``flat`` (place -> value), grouped or dotted."""
    known = set(user_settings())
    unknown = []
    for key, value in source.items():
        items = (
            {f"{key}.{k}": v for k, v in value.items()}
            if key in _GROUPS and isinstance(value, dict)
            else {key: value}
        )
        for place, v in items.items():
            if place in known:
                flat[place] = v
            else:
                _refuse_old(place)
                unknown.append(place)
    if unknown:
        raise InputError(f"unknown config option(s) {sorted(unknown)}; known: {', '.join(known)}")


def _refuse_old(key: str) -> None:
    """InputError naming what an old key is now: a setting renamed, or a constant."""
    if key in _RENAMED:
        raise InputError(f"config key {key!r} was renamed: use {_RENAMED[key]!r}")
    place = _RETIRED_FLAT.get(key, key)
    if place in _RETIRED:
        raise InputError(f"config key {key!r} is no longer a setting: it is the constant {_RETIRED[place]}")


def _bad(name, ref, value):
    raise InputError(f"config option {name!r} must be like {ref!r}, got {value!r}")


def _coerce(place: str, ref, v):
    """``v`` as the type of the default ``ref``; InputError naming ``place`` when it is not."""
    try:
        if place in _STR_LISTS:
            items = str(v).split(",") if isinstance(v, str) else list(v)
            return tuple(dict.fromkeys(str(x).strip() for x in items if str(x).strip()))
        if isinstance(ref, bool):
            if not isinstance(v, bool):
                raise TypeError
            return v
        if isinstance(ref, int):
            if isinstance(v, bool) or int(v) != float(v):
                raise TypeError
            return int(v)
        if isinstance(ref, float):
            if isinstance(v, bool):
                raise TypeError
            return float(v)
        return str(v)
    except (TypeError, ValueError):
        _bad(place, ref, v)


#: (setting, test, what it must be) for each bound a setting has.
_BOUNDS = (
    ("drape.edge_length", lambda v: 0.005 <= v <= 0.1, "within 0.005-0.1 m"),
    ("drape.dt", lambda v: 0 < v <= 0.2, "in (0, 0.2] s"),
    ("area", lambda v: v in AREA_MODES, f"one of {', '.join(AREA_MODES)}"),
    ("side_seams", lambda v: v in SIDE_SEAM_MODES, f"one of {', '.join(SIDE_SEAM_MODES)}"),
    ("band_gap", lambda v: v in BAND_GAP_MODES, f"one of {', '.join(BAND_GAP_MODES)}"),
    ("time_limit", lambda v: v >= 0, ">= 0 s (0: no limit)"),
    ("checks.mesh_spread", lambda v: 0 <= v < 0.5, "in [0, 0.5)"),
    ("optimizer.lr", lambda v: v > 0, "positive"),
    ("material.lr", lambda v: v > 0, "positive"),
    *((p, lambda v: v >= 0, ">= 0") for p in ("drape.sew_steps", "drape.settle_steps", "loss.open",
                                             "loss.seam", "loss.material", "loss.stretch")),
    *((p, lambda v: v >= 1, "at least 1") for p in ("drape.steps", "optimizer.iterations",
                                                    "loss.target_points")),
)  # fmt: skip


def _value(cfg: FitConfig, place: str):
    g, _, n = place.partition(".")
    return getattr(getattr(cfg, g), n) if n else getattr(cfg, g)


def _check(cfg: FitConfig) -> None:
    """InputError naming the first setting out of its bounds, or an unknown material."""
    for place, ok, what in _BOUNDS:
        v = _value(cfg, place)
        if not ok(v):
            raise InputError(f"{place} must be {what}, got {v!r}")
    material_mask(cfg.material.fit)
    if cfg.material.start != "auto":
        get_material(cfg.material.start)  # InputError naming the library's materials
    material_candidates(cfg.material.candidates)


def material_candidates(names) -> tuple[str, ...]:
    """The library materials ``material.start: auto`` tries: ``names`` (a list, or a comma
    string) or, when empty, every distinct material of the library (aliases dropped). Raises
    InputError on an unknown name."""
    names = [n.strip() for n in (names.split(",") if isinstance(names, str) else names) if n.strip()]
    if not names:
        seen = set()
        for n, m in MATERIALS.items():
            if id(m) not in seen:
                seen.add(id(m))
                names.append(n)
    for n in names:
        get_material(n)
    return tuple(dict.fromkeys(names))


def material_mask(names, *, name: str = "material.fit") -> tuple[bool, ...]:
    """Which entries of Gamma a list of names (e.g. ``("H22", "k")`` or ``"H22,k"``) frees, in
    GAMMA_NAMES order; all False for an empty list. Raises InputError on an unknown name."""
    names = [n.strip() for n in (names.split(",") if isinstance(names, str) else names) if n.strip()]
    bad = sorted(set(names) - set(GAMMA_NAMES))
    if bad:
        raise InputError(
            f"{name} {names!r} must list entries of {', '.join(GAMMA_NAMES)} (or none: material fixed)"
        )
    return tuple(n in names for n in GAMMA_NAMES)
