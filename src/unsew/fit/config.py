"""Configuration of a fit: frozen dataclasses, one per concern, every field with its unit, read
from and written to YAML so a result folder holds everything needed to rerun it (STYLE.md habit 13).

A config file groups its options (``drape:``, ``material:``, ``optimizer:``, ``loss:``,
``checks:``, ``output:``); the flat files of earlier versions (``iterations: 100``,
``sew_steps: 80``, ``seam_loss: false``, ...) still load, each old name mapped onto its group
(:data:`LEGACY_KEYS`).

Defaults follow the paper (4.1): Adam with learning rate 1e-3, betas (0.9, 0.999),
lambda_open 0.1, lambda_mat 0.01, dt 0.05 s, 10-20 steps per drape; except the seam weight, 1.0
here instead of the paper's 0.01, and the starting material, which the paper has the user pick
from the library and ``material.start: auto`` picks by draping (docs/decisions/001 and 002).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, fields
from pathlib import Path

from unsew.errors import InputError
from unsew.fit.contact import CONTACT_MODES

# how grading reads a waistband's target loop (``band_gap``)
from unsew.grading.band_gap import BAND_GAP_MODES
from unsew.sim.drape import DrapeSettings
from unsew.sim.solve import resolve_backend
from unsew.sim.material import MATERIALS, get_material

__all__ = [
    "FitConfig",
    "MaterialSettings",
    "OptimizerSettings",
    "LossWeights",
    "CheckSettings",
    "OutputSettings",
    "load_config",
    "config_to_dict",
    "material_mask",
    "material_candidates",
    "GAMMA_NAMES",
    "LEGACY_KEYS",
]

#: Names of the entries of Gamma, in order (unsew.sim.material.Material.gamma()).
GAMMA_NAMES = ("H00", "H01", "H11", "H22", "k")


@dataclass(frozen=True)
class MaterialSettings:
    """The fabric: where the fit starts and what phase two may change of it."""

    #: a library name (the paper's user choice), or "auto": the fabric whose drape of the graded pattern lies
    #: closest to the target, its stiffness then refined (docs/decisions/002)
    start: str = "auto"
    candidates: tuple[str, ...] = ()  #: library materials "auto" tries (empty: every material in the library)
    #: "auto": how many of the best candidates other than cotton are graded again in their own fabric [-]
    regrade: int = 2
    #: "auto": steps (at drape.dt) each candidate fabric settles from the drape it is tried on; 0: dressed
    #: from scratch [-]
    warm_steps: int = 40
    #: "auto": the chosen pattern and fabric dressed from scratch; clearly farther (0.5 mm and 10 %) than the
    #: cotton-graded pattern: start from that one (unsew.fit.material._checked) [-]
    check: bool = True
    #: "auto": rounds of the stiffness search after the choice (stretch and bending scaled by 1/s and s, s =
    #: 2, sqrt 2, ...); 0: off [-]
    refine: int = 2
    #: entries of Gamma phase two moves (the others keep the start's value, H01 its ratio to sqrt(H00 H11));
    #: empty: the material stays fixed
    fit: tuple[str, ...] = GAMMA_NAMES
    start_iteration: int = 20  #: iteration at which the material joins the variables [-]
    lr: float = 5e-2  #: Adam learning rate of the log-material parameters [-]


#: What the fit does with the target's surface area (``area``).
AREA_MODES = ("free", "target")

#: What grading does with the side seams (``side_seams``; unsew.grading.grade.SIDE_SEAM_MODES).
SIDE_SEAM_MODES = ("none", "girth")

#: What phase two may change of a waistband (``optimizer.bands``).
BAND_MODES = ("free", "height", "held")

#: How phase two treats the lengths of stitched edges (``optimizer.seams``).
SEAM_MODES = ("held", "soft", "trued")


@dataclass(frozen=True)
class OptimizerSettings:
    """Phase two's Adam loop and its stopping rule."""

    iterations: int = 100  #: iteration budget [-]
    lr: float = 1e-3  #: Adam learning rate of the control points [m per step]
    #: factor the learning rates fall to, geometrically, over `iterations` [-] (1 = constant)
    lr_decay: float = 1.0
    betas: tuple[float, float] = (0.9, 0.999)  #: Adam betas [-]
    pattern_start: int = 0  #: iteration at which the control points K start to move [-]
    #: start each drape from the previous iteration's (the paper); False: always from the graded drape
    warm_start: bool = True
    #: slip speed below which friction is viscous in phase two's drapes (only) [m/s]
    friction_eps: float = 1e-2
    #: a control point of a panel narrower than this (area / half perimeter) moves by lr x width / panel_width
    #: per step (waistbands: 3.6 cm, x0.36); 0: every point at lr [m]
    panel_width: float = 0.1
    #: what phase two may change of a waistband (a panel open only along its top): "free" anything, "height"
    #: its girth only, "held" nothing (docs/decisions/013)
    bands: str = "free"
    #: stitched edge lengths: "soft" pulled by the seam loss; "held" put back in the graded ratio after every
    #: step; "trued" once, on the best iterate (unsew.pattern.seams; docs/decisions/013)
    seams: str = "soft"
    tol: float = 1e-3  #: stop when the loss changed by less than this fraction over `patience` iterations [-]
    patience: int = 15  #: iterations over which convergence is judged [-]
    #: > 0: phase two's control-point steps are line searched (a step raising the loss is retried at half
    #: length, at most this many times, else not taken; lr: the move of the point moving most;
    #: docs/decisions/018); 0: Adam's steps, every one kept (the paper) [-]
    retries: int = 3
    #: > 0: phase two starts from a drape at rest, the graded drape draped on until its 99th-percentile vertex
    #: speed falls below this; 0: off (docs/decisions/013) [m/s]
    rest_speed: float = 0.0
    rest_steps: int = 160  #: most steps the graded drape is let settle before phase two [-]


@dataclass(frozen=True)
class LossWeights:
    """Weights of the loss terms (eqs. 5-9); a weight of 0 drops its term."""

    curvature_weighted: bool = True  #: curvature-weighted Chamfer, eq. 7 (ablation: plain Chamfer)
    open: float = 0.1  #: open-contour Chamfer, eq. 6 [-]
    seam: float = 1.0  #: seam-length loss, eq. 8 [-] (paper: 0.01; docs/decisions/001)
    material: float = 0.01  #: material range penalty [-]
    #: pull towards the graded pattern: mean squared 2D rest-vertex move [m^2] (0: the paper's loss) [-]
    prior: float = 0.0
    #: pull of the pattern's total area towards the target's surface area, (A / A_T - 1)^2 (unsew.losses.area;
    #: 0: off, docs/decisions/013) [m^2]
    area: float = 0.0
    #: pull of each panel's rest area towards its graded area, mean of (A_p / A_p0 - 1)^2
    #: (unsew.losses.panel_area; 0: off, docs/decisions/013) [-]
    panel_area: float = 0.0
    #: barrier against overstretched cloth, sum over drape edges of relu(stretch - stretch_bound)^2
    #: (unsew.losses.stretch; not in the paper; docs/decisions/006) [-]
    stretch: float = 1e-4
    stretch_bound: float = 1.5  #: edge stretch (length over rest length) the barrier lets pass free [-]
    target_points: int = 8000  #: target vertices kept for the Chamfer (random subset, seeded) [-]


@dataclass(frozen=True)
class CheckSettings:
    """Checks after phase two (not in the paper)."""

    #: dress the fitted pattern from scratch; unless it lies closer to the target than the graded drape,
    #: return the graded pattern
    redress: bool = True
    #: dress the returned pattern on meshes of edge length x (1 -/+ mesh_spread) and report their distance to
    #: the target (0: skip) [-]
    mesh_spread: float = 0.04
    #: meshes the re-dress check judges on: 3, both patterns dressed from scratch on the fit's mesh and the
    #: mesh spread's two, means compared; 1, the fit's mesh alone (unsew.fit.checks; docs/decisions/005) [-]
    redress_meshes: int = 3


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
    #: mesh edge length of the candidate drapes of the automatic base choice [m]
    base_choice_edge: float = 0.04
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
    #: "default": drape.contact_stiffness below drape.contact_threshold; "target": the threshold at the
    #: target's gap to the body, a stiffer contact (unsew.fit.contact; docs/decisions/012)
    contact: str = "default"
    seed: int = 0  #: seed of every random choice [-]
    device: str = "cpu"  #: torch device for the simulation ("cpu", "cuda")
    #: seconds the fit aims to end within, from the command's start; the material choice's optional steps,
    #: phase two's iterations, the three-mesh re-dress and the mesh spread give way (unsew.fit.budget); 0: no
    #: limit [s]
    time_limit: float = 540.0
    drape: DrapeSettings = field(default_factory=DrapeSettings)  #: meshing, sewing, settling and drape steps
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

#: Option names of the flat config files of earlier versions -> their place (group.field).
LEGACY_KEYS = {
    "edge_length": "drape.edge_length", "dt": "drape.dt", "steps": "drape.steps",
    "sew_steps": "drape.sew_steps", "settle_steps": "drape.settle_steps", "material": "material.start",
    "material_candidates": "material.candidates", "material_regrade": "material.regrade",
    "material_refine": "material.refine", "material_params": "material.fit",
    "material_start": "material.start_iteration", "lr_material": "material.lr",
    "iterations": "optimizer.iterations", "lr": "optimizer.lr", "lr_decay": "optimizer.lr_decay",
    "betas": "optimizer.betas", "pattern_start": "optimizer.pattern_start",
    "warm_start": "optimizer.warm_start", "fit_friction_eps": "optimizer.friction_eps",
    "tol": "optimizer.tol", "patience": "optimizer.patience",
    "curvature_weighted": "loss.curvature_weighted", "lambda_open": "loss.open", "lambda_seam": "loss.seam",
    "lambda_mat": "loss.material", "lambda_prior": "loss.prior", "target_points": "loss.target_points",
    "redress_check": "checks.redress", "mesh_spread": "checks.mesh_spread",
    "redress_meshes": "checks.redress_meshes", "report": "output.report",
}  # fmt: skip
#: Old on/off switches, now a weight of 0 or an empty list: name -> (place, value when False).
_LEGACY_SWITCHES = {"seam_loss": ("loss.seam", 0.0), "optimize_material": ("material.fit", ())}
_STR_LISTS = {"material.candidates", "material.fit"}


def config_to_dict(cfg: FitConfig) -> dict:
    """Plain nested dict (YAML-ready: lists, not tuples) of a config."""
    return _lists(dataclasses.asdict(cfg))


def _lists(v):
    if isinstance(v, dict):
        return {k: _lists(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_lists(x) for x in v]
    return v


def load_config(path: str | Path | None = None, *, defaults: dict | None = None, **overrides) -> FitConfig:
    """Read a YAML config and apply keyword overrides (None values are ignored).

    Precedence: overrides > the file > ``defaults`` > FitConfig's own defaults. Each source may
    be grouped (``{"optimizer": {"iterations": 9}}``), dotted (``{"optimizer.iterations": 9}``) or
    use the old flat names (``{"iterations": 9}``, :data:`LEGACY_KEYS`). Unknown keys and values
    of the wrong type raise InputError naming the key.
    """
    flat: dict = {}
    names: dict = {}  # place -> the name the user gave it (for messages)
    switches: dict = {}
    for source in (
        defaults or {},
        _read_yaml(path) if path is not None else {},
        {k: v for k, v in overrides.items() if v is not None},
    ):
        _flatten(source, flat, names, switches)
    for key, on in switches.items():
        place, off = _LEGACY_SWITCHES[key]
        if not on:
            flat[place], names[place] = off, key
    groups: dict = {g: {} for g in _GROUPS}
    top: dict = {}
    for place, value in flat.items():
        g, _, name = place.partition(".")
        ref = getattr(FitConfig(), g) if name else FitConfig()
        value = _coerce(place, getattr(ref, name or g), value, names.get(place, place))
        (groups[g] if name else top)[name or g] = value
    cfg = FitConfig(**top, **{g: _GROUPS[g](**kw) for g, kw in groups.items()})
    _check(cfg, names)
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


def _flatten(source: dict, flat: dict, names: dict, switches: dict) -> None:
    """Add ``source``'s options to ``flat`` (place -> value), whatever their spelling."""
    known_top = {f.name for f in fields(FitConfig)} - set(_GROUPS)
    unknown = []
    for key, value in source.items():
        if key in _GROUPS and isinstance(value, dict):
            group_fields = {f.name for f in fields(_GROUPS[key])}
            for k, v in value.items():
                if k in group_fields:
                    flat[f"{key}.{k}"] = v
                    names[f"{key}.{k}"] = f"{key}.{k}"
                else:
                    unknown.append(f"{key}.{k}")
        elif key in _LEGACY_SWITCHES:
            switches[key] = value if isinstance(value, bool) else _bad(key, True, value)
        elif key in LEGACY_KEYS:
            flat[LEGACY_KEYS[key]] = value
            names[LEGACY_KEYS[key]] = key
        elif key in known_top or (
            "." in key
            and key.split(".", 1)[0] in _GROUPS
            and key.split(".", 1)[1] in {f.name for f in fields(_GROUPS[key.split(".", 1)[0]])}
        ):
            flat[key] = value
            names[key] = key
        else:
            unknown.append(key)
    if unknown:
        raise InputError(f"unknown config option(s) {sorted(unknown)}; known: {', '.join(_known())}")


def _known() -> list[str]:
    out = [f.name for f in fields(FitConfig) if f.name not in _GROUPS]
    for g, make in _GROUPS.items():
        out += [f"{g}.{f.name}" for f in fields(make)]
    return out


def _bad(name, ref, value):
    raise InputError(f"config option {name!r} must be like {ref!r}, got {value!r}")


def _coerce(place: str, ref, v, name: str):
    """``v`` as the type of the default ``ref``; InputError naming ``name`` when it is not."""
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
        if isinstance(ref, tuple):
            out = tuple(float(x) for x in v)
            if len(out) != len(ref):
                raise TypeError
            return out
        return str(v)
    except (TypeError, ValueError):
        _bad(name, ref, v)


def _check(cfg: FitConfig, names: dict) -> None:
    def say(place: str) -> str:
        return names.get(place, place)

    d, o = cfg.drape, cfg.optimizer
    if not 0.005 <= d.edge_length <= 0.1:
        raise InputError(f"{say('drape.edge_length')} {d.edge_length} m is outside 0.005-0.1 m")
    if d.dt <= 0 or d.dt > 0.2:
        raise InputError(f"{say('drape.dt')} {d.dt} s must be in (0, 0.2]")
    try:  # "cholmod" asked for where scikit-sparse is missing: the install line, before any drape
        resolve_backend(d.backend)
    except (ValueError, ImportError) as exc:
        raise InputError(f"{say('drape.backend')}: {exc}") from None
    if cfg.area not in AREA_MODES:
        raise InputError(f"{say('area')} must be one of {', '.join(AREA_MODES)}, got {cfg.area!r}")
    if cfg.side_seams not in SIDE_SEAM_MODES:
        raise InputError(
            f"{say('side_seams')} must be one of {', '.join(SIDE_SEAM_MODES)}, got {cfg.side_seams!r}"
        )
    if cfg.band_gap not in BAND_GAP_MODES:
        raise InputError(
            f"{say('band_gap')} must be one of {', '.join(BAND_GAP_MODES)}, got {cfg.band_gap!r}"
        )
    if cfg.contact not in CONTACT_MODES:
        raise InputError(f"{say('contact')} must be one of {', '.join(CONTACT_MODES)}, got {cfg.contact!r}")
    if o.bands not in BAND_MODES:
        raise InputError(f"{say('optimizer.bands')} must be one of {', '.join(BAND_MODES)}, got {o.bands!r}")
    if o.seams not in SEAM_MODES:
        raise InputError(f"{say('optimizer.seams')} must be one of {', '.join(SEAM_MODES)}, got {o.seams!r}")
    if not o.friction_eps > 0:
        raise InputError(f"{say('optimizer.friction_eps')} must be positive, got {o.friction_eps} m/s")
    if not cfg.loss.stretch_bound >= 1:
        raise InputError(
            f"{say('loss.stretch_bound')} must be at least 1 (no stretch), got {cfg.loss.stretch_bound}"
        )
    if not cfg.time_limit >= 0:
        raise InputError(f"{say('time_limit')} must be >= 0 s (0: no limit), got {cfg.time_limit}")
    if not 0 <= cfg.checks.mesh_spread < 0.5:
        raise InputError(f"{say('checks.mesh_spread')} must be in [0, 0.5), got {cfg.checks.mesh_spread}")
    if cfg.checks.redress_meshes not in (1, 3):
        raise InputError(f"{say('checks.redress_meshes')} must be 1 or 3, got {cfg.checks.redress_meshes}")
    for place in (
        "material.refine",
        "material.regrade",
        "material.warm_steps",
        "drape.sew_steps",
        "drape.settle_steps",
        "loss.open",
        "loss.seam",
        "loss.material",
        "loss.prior",
        "loss.area",
        "loss.panel_area",
        "loss.stretch",
    ):
        g, n = place.split(".")
        if getattr(getattr(cfg, g), n) < 0:
            raise InputError(f"{say(place)} must be >= 0, got {getattr(getattr(cfg, g), n)}")
    for place in ("drape.steps", "optimizer.iterations", "loss.target_points"):
        g, n = place.split(".")
        if getattr(getattr(cfg, g), n) < 1:
            raise InputError(f"{say(place)} must be at least 1")
    if o.lr <= 0 or cfg.material.lr <= 0:
        raise InputError("learning rates must be positive")
    if not 0 < o.lr_decay <= 1:
        raise InputError(f"{say('optimizer.lr_decay')} {o.lr_decay} must be in (0, 1]")
    if names.get("material.fit") != "optimize_material":
        material_mask(cfg.material.fit, name=say("material.fit"))
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
