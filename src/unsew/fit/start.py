"""Phase one of the fit (paper 3.3): the base pattern sized to the wearer, dressed on the body and
graded to the target's open contours. Its hand-off is a :class:`Start`.

The base is the user's (``--base NAME|P.json``) or, by default, chosen by draping
(:func:`choose_base`): every base of the library of the target's garment type
(:func:`unsew.pattern.base.bases_for`) is dressed on the wearer on a coarse mesh in the start
material, and the one whose drape lies closest to the target (mean surface Chamfer) is kept, as
the material is chosen (:mod:`unsew.fit.material`). A base whose drape has no opening on an arm
where the target has one, or the other way round (a sleeveless base for a sleeved target), is
chosen only when no candidate's arms agree with the target's: grading cannot grow or remove a
sleeve, and it would pull the armhole out to the target's cuff. Dresses are told apart by the
cloth over the torso (:data:`TORSO_CHOICE`): their bases differ at the waist, which grading does
not reach. When the runner-up lies within :data:`BASE_TIE` of the best, the call is within the
candidates' own noise, and :func:`start_chosen` grades both and starts from the runner-up's
graded drape when it is clearly closer to the target."""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from unsew.body.measure import measure_body
from unsew.dress import dress, held_anchors, settle
from unsew.errors import InputError
from unsew.fit.config import FitConfig
from unsew.fit.progress import Progress
from unsew.fit.scene import FitContext, Scene
from unsew.fit.target import Target
from unsew.grading.contours import place_contours
from unsew.grading.design_reading import read_design
from unsew.grading.garment_type import V_ANGLE_DEG, read_garment_type, read_necklines
from unsew.grading.grade import GradingSettings, grade
from unsew.io.garmentcode import load_pattern
from unsew.losses.contours import open_contours
from unsew.pattern.base import BASES, bases_for, garment_of, make_base_pattern
from unsew.pattern.base._frame import body_frame
from unsew.pattern.design import GARMENTS
from unsew.sim.checks import check_dressed

__all__ = [
    "Start",
    "start",
    "base_pattern_for",
    "BaseChoice",
    "choose_base",
    "arm_openings",
    "ARM_PARTS",
    "SLEEVE_REACH",
    "SLEEVE_NEAR",
    "TORSO_CHOICE",
    "TORSO_BAND_BELOW_ARMPIT",
    "BASE_TIE",
    "start_chosen",
    "BASE_CHOICE_EDGE",
    "WARM_STEPS",
    "GRADING_ASTRAY",
    "GRADING_ASTRAY_MM",
    "graded_astray",
]

#: mesh edge length of the candidate drapes of the automatic base choice [m]
BASE_CHOICE_EDGE = 0.04
#: A graded drape farther from the target than GRADING_ASTRAY times the base's drape and
#: GRADING_ASTRAY_MM [mm] more is refused, and phase two starts from the base: grading moved the
#: garment off its place (a circle skirt's graded drape on the shoulders, docs/decisions/043)
GRADING_ASTRAY = 2.0
GRADING_ASTRAY_MM = 20.0
#: steps (at drape.dt) a drape in another fabric settles from one already dressed (the base's for
#: grading in it, the graded pattern's for the material choice); 0: dressed from scratch [-]
WARM_STEPS = 40

#: garment types a base pattern may stand in for (same panel topology)
_COMPATIBLE = {
    "tshirt": {"tshirt", "dress"},
    "dress": {"dress", "tshirt"},
    "pants": {"pants", "shorts"},
    "shorts": {"shorts", "pants"},
    "skirt": {"skirt"},
}


@dataclass(frozen=True)
class Start:
    """Where phase two starts from.

    base: the base Pattern; graded: the graded pattern U_LG (the base itself without grading);
    mesh: its GarmentMesh; x: its drape X_LG (n_x, 3) float64 [m] on ``mesh``; grade_table: the
    contour rows of grading; x_base, mesh_base: the base pattern's drape and mesh; material: the
    Material all of these were dressed in; base_name, base_choice: which base, and how it was chosen;
    dress_s: how long the base took to dress from scratch [s] (0: settled from another drape), the
    fit's estimate of a drape from scratch (:mod:`unsew.fit.budget`).
    """

    base: object
    graded: object
    mesh: object
    x: np.ndarray
    grade_table: list
    x_base: np.ndarray
    mesh_base: object
    material: object
    base_name: str = ""  #: the base's library name or JSON path
    base_choice: tuple = ()  #: the automatic base choice's rows, best first (BaseChoice.table)
    dress_s: float = 0.0  #: seconds the base's drape from scratch took [s] (0: not dressed from scratch)
    #: the vertices ``x`` holds at their height (``Cloth.anchors``, :func:`unsew.dress.held_anchors`)
    anchors: tuple | None = None

    def replace(self, **changes) -> "Start":
        return dataclasses.replace(self, **changes)


def with_garment_read(case, cfg: FitConfig, *, log=print):
    """``case`` itself when meta.json names a garment type the library has bases of or
    ``cfg.base`` names a base; else a copy whose garment type is read off the target
    (:func:`unsew.grading.garment_type.read_garment_type`), with the reading in its notes and the
    design read (:func:`unsew.grading.design_reading.read_design`) as ``design``: the base is then
    chosen among designs drafted from it (:func:`choose_base`). A type named without library bases
    (a jumpsuit) keeps its name, its design read off the target. Raises InputError for a type the
    design space has no designs of."""
    if cfg.base or case.garment in BASES or getattr(case, "design", None) is not None:
        return case  # a base named, a type with library bases, or the design read already
    reading = read_garment_type(case.target_verts, case.target_faces, case.body.skeleton)
    design = read_design(
        case.target_verts, case.target_faces, case.body.skeleton, reading=reading, body=case.body
    )
    if case.garment:  # named in meta.json: the name stands, the cut is read
        log(
            f"meta.json names a {case.garment} (no library base): its design is read off the target, "
            f"which reads as a {reading.garment} ({reading.reason})"
        )
        design = dataclasses.replace(design, garment=case.garment)
        log(design.summary())
        return dataclasses.replace(case, design=design)
    note = f"garment type read off the target: {reading.garment}: {reading.reason}"
    if reading.garment not in GARMENTS:
        raise InputError(
            f"the target reads as a {reading.garment} ({reading.reason}); there are no "
            f"{reading.garment} designs: pass --base P.json"
        )
    log(note)
    log(design.summary())
    return dataclasses.replace(case, garment=reading.garment, garment_note=note, design=design)


def base_pattern_for(case, cfg: FitConfig):
    """The base pattern the user named: cfg.base (a garment type, a library base name of
    :data:`unsew.pattern.base.BASES`, or a GarmentCode JSON path) or, when cfg.base is empty,
    meta.json's garment's default base, sized to the wearer's measurements. Refuses a library base
    of the wrong garment type."""
    base = cfg.base or case.garment
    if not base:
        raise InputError(f"no base pattern: meta.json names no garment; pass --base {'|'.join(BASES)}|P.json")
    if base in BASES:
        g = garment_of(base)
        if case.garment and case.garment not in _COMPATIBLE[g]:
            raise InputError(
                f"base pattern {base!r} cannot make a {case.garment} target (meta.json); "
                f"use --base {case.garment}"
            )
        return make_base_pattern(base, measure_body(case.body), waist_point=cfg.side_seams == "girth")
    p = Path(base)
    if p.suffix.lower() != ".json":
        raise InputError(
            f"--base {base!r} is neither a base pattern ({', '.join(BASES)}) nor a .json pattern"
        )
    return load_pattern(p)


#: body parts whose openings a base must share with the target (sleeves; :func:`arm_openings`)
ARM_PARTS = ("left_arm", "right_arm")
#: how far beyond the shoulder joint along the upper arm [m] an opening on an arm must lie to be
#: a sleeve's: an armhole's centre lies within 4 cm of the joint, on the shoulder bone or on the
#: arm (which of the two flips with the mesh); a short sleeve's cuff about 20 cm down the arm,
#: a cap sleeve's about 9 cm
SLEEVE_REACH = 0.06
#: ... and how near a bone of that arm [m] (a coarse drape's cuff may hang off the arm's line,
#: and be placed on another bone)
SLEEVE_NEAR = 0.12


def arm_openings(verts, faces, skeleton, *, contours=None) -> tuple[int, int]:
    """How many open contours of a garment surface (verts (V, 3) [m], faces (F, 3)) are sleeve
    openings on the left and on the right arm: within :data:`SLEEVE_NEAR` of a bone of the arm
    (a candidate of :func:`unsew.grading.contours.place_contours`) and at least
    :data:`SLEEVE_REACH` beyond the shoulder joint. (1, 1) for a tee, (0, 0) for a sleeveless top."""
    placed = place_contours(verts, faces, skeleton, contours=contours)
    bones = skeleton.bones()
    counts = []
    for side in ARM_PARTS:
        arm = {b.name: b for b in bones if b.part == side}
        root = next((b for b in arm.values() if b.parent not in arm), None)
        counts.append(
            0
            if root is None
            else sum(
                1
                for pc in placed
                if any(b.part == side and h < SLEEVE_NEAR for b, _, h in pc.candidates)
                and float((pc.centre - root.a) @ root.direction) >= SLEEVE_REACH
            )
        )
    return tuple(counts)


#: Garment types whose bases are chosen on the cloth over the torso between the hips and
#: :data:`TORSO_BAND_BELOW_ARMPIT` under the armpits (:meth:`Target.band_distance_mm`), not on the
#: whole garment. Grading moves a garment's openings (hem, neckline, cuffs) and the cloth next to
#: them; the dresses' bases differ at the waist (waisted and flared, or straight), between the
#: openings, where grading leaves them. On the whole garment the straight dress, whose hem lies
#: nearer most targets' before grading, was chosen for waisted dresses, and their fits ended
#: farther (docs/decisions/007).
TORSO_CHOICE = ("dress",)
TORSO_BAND_BELOW_ARMPIT = 0.05  #: [m]
#: A runner-up base whose drape lies within this ratio of the best's (on the distance the choice is
#: made on, with the same arms) is a tie: both are graded and the runner-up kept when its graded
#: drape is clearly closer (:func:`start_chosen`): the candidates' distances move by more than
#: that with their coarse mesh alone (docs/decisions/007).
BASE_TIE = 1.10


@dataclass(frozen=True)
class BaseChoice:
    """The base pattern phase one starts from: ``pattern``, its ``name`` (a library base, or the
    JSON path given), and the automatic choice's table, best first: rows {"base", "chamfer_mm",
    "arms"} (arms: True when the drape's openings on the arms are the target's, :func:`arm_openings`;
    a candidate whose drape failed has chamfer_mm None and an "error"), and "torso_mm" (the distance
    over the torso the choice was made on) for the types of :data:`TORSO_CHOICE`; empty when the
    user named the base. ``seconds``: time the choice took [s]. ``tie``: the runner-up's (name,
    pattern) when it lies within :data:`BASE_TIE` of the best, else None."""

    pattern: object
    name: str
    table: list = field(default_factory=list)
    seconds: float = 0.0
    tie: tuple | None = None


def choose_base(
    case, target: Target, sdf, cfg: FitConfig, material, *, progress: Progress, log=print
) -> BaseChoice:
    """The base pattern of the fit: the user's (cfg.base) or, when cfg.base is empty and the
    library has several bases of meta.json's garment type, the one whose drape lies closest to
    the target (over the torso for :data:`TORSO_CHOICE`). Each candidate, sized to the wearer, is
    dressed from scratch on a mesh of edge :data:`BASE_CHOICE_EDGE` [m] (the rest of ``cfg.drape``
    as the fit's drapes) in ``material`` (the start material); its distance is
    :meth:`Target.distance_mm` (:meth:`Target.band_distance_mm` over the torso). A candidate whose drape
    fails or is judged bad (:func:`unsew.sim.checks.check_dressed`) is listed, not chosen.
    When the garment type was read off the target (``case.design``, :func:`with_garment_read`)
    the candidates are designs drafted from that reading
    (:func:`unsew.fit.designs.drafted_candidates`), not the library's bases."""
    reading = getattr(case, "design", None)
    if cfg.base or (reading is None and (not case.garment or case.garment not in BASES)):
        return BaseChoice(base_pattern_for(case, cfg), cfg.base or case.garment)
    m = measure_body(case.body)
    garment, names, make = _candidates(case, target, cfg, m, log)
    if len(names) == 1:
        return BaseChoice(make(names[0]), names[0])
    t0 = time.perf_counter()
    frame = body_frame(m)
    band = (frame.hip_y, frame.armpit_y - TORSO_BAND_BELOW_ARMPIT) if garment in TORSO_CHOICE else None
    scene = Scene(case.body, target, sdf, cfg, progress, log)
    want = arm_openings(target.verts, target.faces, case.body.skeleton, contours=target.contours)
    rows, patterns = [], {}
    for name in names:
        pat = make(name)
        row = _candidate(name, pat, scene, material, want, band)
        rows.append(row)
        if row.get("chamfer_mm") is not None:
            patterns[name] = pat
    if not patterns and reading is not None and case.garment in BASES:  # no drafted design dresses here
        log(
            f"no design drafted from the reading could be dressed; the library's {case.garment} bases instead"
        )
        return choose_base(_without_design(case), target, sdf, cfg, material, progress=progress, log=log)
    _require_one_dressed(rows, patterns, case.garment)
    on_torso = bool(band) and all(r.get("torso_mm") is not None for r in rows if r["base"] in patterns)
    # the arms agreeing first, when any candidate's do; then the closest (over the torso when
    # every candidate and the target have cloth there: a skeleton without torso bones has none)
    any_arms = any(r.get("arms") and r["base"] in patterns for r in rows)
    key = "torso_mm" if on_torso else "chamfer_mm"
    rows, key = _ranked(rows, patterns, key, any_arms, skirts=on_torso and reading is not None)
    tie = _tie(rows, patterns, key, any_arms)
    how = _how(band, on_torso, tie, skirts=key != "torso_mm" and on_torso)
    best = rows[0]["base"]
    log(
        "base: "
        + ", ".join(_said(r, patterns) for r in rows)
        + f"; {best} chosen (target: {want[0]} + {want[1]} openings on the arms"
        + how
        + ")"
    )
    return BaseChoice(patterns[best], best, rows, time.perf_counter() - t0, tie)


def _candidates(case, target: Target, cfg: FitConfig, m, log) -> tuple[str, list, Callable]:
    """(garment type, candidate names, name -> its Pattern sized to measurements ``m``): the
    designs drafted from ``case.design`` when the type was read off the target, else the
    library's bases of ``case.garment``, their necklines read off the target."""
    reading = getattr(case, "design", None)
    if reading is not None:
        from unsew.fit.designs import drafted_candidates, read_measures

        measures = read_measures(target.verts, target.faces, case.body.skeleton, contours=target.contours)
        patterns = drafted_candidates(reading, m, measures=measures)
        if not patterns:
            raise InputError(f"no {reading.garment} design drafts for this body; pass --base P.json")
        log(f"designs drafted from the reading: {', '.join(patterns)}")
        return reading.garment, list(patterns), patterns.__getitem__
    garment = garment_of(case.garment)
    necklines = _necklines(garment, target, case.body, log)

    def make(name):
        return make_base_pattern(name, m, waist_point=cfg.side_seams == "girth", necklines=necklines)

    return garment, bases_for(garment), make


def _without_design(case):
    """``case`` without its design reading: the library's bases of its garment type are its candidates."""
    if dataclasses.is_dataclass(case):
        return dataclasses.replace(case, design=None)
    return type(case)(**{**vars(case), "design": None})


def _require_one_dressed(rows: list, patterns: dict, garment: str) -> None:
    """InputError listing each candidate's reason when none of them could be dressed."""
    if patterns:
        return
    why = "; ".join(
        f"{r['base']}: {r.get('error') or 'its distance to the target is not finite'}" for r in rows
    )
    raise InputError(
        f"no base pattern of type {garment} could be dressed on this body ({why}); pass --base P.json"
    )


def _how(band: tuple | None, on_torso: bool, tie: tuple | None, *, skirts: bool = False) -> str:
    """How the base was chosen, for the log: on the torso ``band`` (heights [m]) or the whole
    garment (``skirts``: among those within BASE_TIE on the torso), and the runner-up graded too
    when ``tie``."""
    how = ""
    if band:
        how = (
            f"; chosen on the torso, {band[0]:.2f}-{band[1]:.2f} m up"
            if on_torso
            else "; no cloth over the torso to compare, chosen on the whole garment"
        )
        if skirts:
            how += f", then on the whole garment among those within {100 * (BASE_TIE - 1):.0f} % there"
    if tie is not None:
        how += f"; {tie[0]} within {100 * (BASE_TIE - 1):.0f} %: both graded"
    return how


def _necklines(garment: str, target: Target, body, log):
    """The neckline cuts of a top read off the target (logged when one was read), or None: the
    neckline's cut is read off the target, not drawn from the library."""
    if garment not in ("tshirt", "dress"):
        return None
    necklines, angles = read_necklines(target.verts, target.faces, body.skeleton, contours=target.contours)
    if angles:
        log(
            f"neckline read off the target: front {necklines[0]}, back {necklines[1]} (the angle at its "
            f"lowest point: front {angles.get('front_deg', 180):.0f} deg, back "
            f"{angles.get('back_deg', 180):.0f} deg; a V under {V_ANGLE_DEG:.0f})"
        )
    return necklines


def _candidate(name: str, pat, scene: Scene, material, want: tuple, band: tuple | None) -> dict:
    """A base choice row: candidate ``pat`` dressed from scratch on a BASE_CHOICE_EDGE mesh, its
    distance [mm] (None: not finite), whether its arm openings are the target's ``want``, its
    distance over the torso ``band`` [m] (heights); {"base", "chamfer_mm": None, "error"} when it
    cannot be dressed here or its drape fails its check."""
    body, target = scene.body, scene.target
    settings = scene.cfg.drape.replace(edge_length=BASE_CHOICE_EDGE)
    try:
        with scene.progress.phase(f"base {name}") as bar:
            d = dress(pat, body, sdf=scene.sdf, material=material, settings=settings, progress=bar)
        verdict = check_dressed(d, body=body)
        if not verdict.ok:  # fallen, exploded, off or inside the body: no candidate
            raise ValueError(verdict.reason)
        cf = target.distance_mm(d.x.numpy(), d.mesh.faces)
        arms = arm_openings(d.x.numpy(), d.mesh.faces, body.skeleton) == want
        torso = target.band_distance_mm(d.x.numpy(), d.mesh.faces, body.skeleton, *band) if band else None
    except (InputError, ValueError, RuntimeError) as exc:  # a candidate that cannot be dressed here
        return {"base": name, "chamfer_mm": None, "error": str(exc).splitlines()[0]}
    row = {"base": name, "chamfer_mm": cf if math.isfinite(cf) else None, "arms": arms}
    if band:
        row["torso_mm"] = torso if math.isfinite(torso) else None
    return row


def _ranked(rows: list, patterns: dict, key: str, any_arms: bool, *, skirts: bool) -> tuple[list, str]:
    """(rows best first, the distance the best and the runner-up are told apart on): the dressed
    first, those whose arms agree with the target's first when any do, then the nearest on
    ``key``. With ``skirts`` (dresses drafted from the reading: they differ below the hips too,
    in the skirt's cut, where the torso band does not look) the candidates lying within
    :data:`BASE_TIE` of the best on the torso are ranked again on the whole garment."""
    rows = sorted(
        rows, key=lambda r: (r["base"] not in patterns, any_arms and not r.get("arms"), r.get(key) or 0.0)
    )
    if not skirts or rows[0]["base"] not in patterns:
        return rows, key
    d0, arms0 = rows[0][key], rows[0].get("arms")
    near = [r for r in rows if r["base"] in patterns and r.get("arms") == arms0 and r[key] <= BASE_TIE * d0]
    if len(near) < 2:
        return rows, key
    near.sort(key=lambda r: r["chamfer_mm"])
    return near + [r for r in rows if r not in near], "chamfer_mm"


def _tie(rows: list, patterns: dict, key: str, any_arms: bool) -> tuple | None:
    """(name, pattern) of the runner-up when it lies within BASE_TIE of the best (rows sorted,
    best first, on ``key``) and its arms agree as well as the best's may, else None."""
    if len(rows) > 1 and rows[1]["base"] in patterns and (rows[1].get("arms") or not any_arms):
        d0, d1 = rows[0].get(key), rows[1].get(key)
        if d0 and d1 and d1 <= BASE_TIE * d0:
            return rows[1]["base"], patterns[rows[1]["base"]]
    return None


def _said(r: dict, patterns: dict) -> str:
    """A base choice row in the log's words."""
    if r["base"] not in patterns:
        return f"{r['base']} failed"
    torso = r.get("torso_mm")
    return (
        f"{r['base']} {r['chamfer_mm']:.2f} mm"
        + (f" (torso {torso:.2f} mm)" if torso is not None else "")
        + ("" if r["arms"] else " (arms differ)")
    )


def start_chosen(choice: BaseChoice, scene: Scene, material, *, budget=None) -> Start:
    """Phase one from the base choice: :func:`start` from ``choice.pattern`` and, when the choice
    was a tie (``choice.tie``) and ``budget`` (a :class:`unsew.fit.budget.TimeBudget`) has more
    than half its limit left, from the runner-up too, when a grading as long as the first still
    fits the limit. The runner-up's Start is kept when its graded
    drape lies closer to the target (:meth:`Target.distance_mm`) than the chosen base's by more
    than :data:`unsew.fit.material.CHECK_MARGIN_MM` and ``CHECK_MARGIN_REL`` of it (what two drapes
    from scratch of one pattern differ by); otherwise the chosen base's. The graded distances
    [mm] go into the base choice table's rows ("graded_mm"); a runner-up whose grading fails (or
    diverges) is logged and left out."""
    names = [choice.name] + ([choice.tie[0]] if choice.tie else [])
    patterns = [choice.pattern] + ([choice.tie[1]] if choice.tie else [])
    if choice.tie and budget is not None and not budget.within(0.5):
        budget.cut(f"base choice: {choice.tie[0]} not graded (half the limit spent)")
        names, patterns = names[:1], patterns[:1]
    starts, graded_s = [], 0.0
    for name, pattern in zip(names, patterns):
        if starts and budget is not None and not budget.fits(graded_s):  # the first's grading as estimate
            budget.cut(f"base choice: {name} not graded (its grading, about {graded_s:.0f} s, would overrun)")
            break
        t0 = time.perf_counter()
        try:
            s = start(
                pattern,
                scene,
                material,
                garment=name,
                log=scene.log,
                label="drape base" if not starts else f"drape base {name}",
            )
        except (InputError, ValueError, RuntimeError) as exc:  # the runner-up's failure is no fit's
            if not starts:
                raise
            scene.log(f"base {name}: grading failed ({str(exc).splitlines()[0]}); left out")
            continue
        graded_s = time.perf_counter() - t0
        starts.append((scene.target.distance_mm(s.x, s.mesh.faces) if len(names) > 1 else math.nan, name, s))
    table = [dict(r) for r in choice.table]
    for cf, name, _ in starts:
        for r in table:
            if r["base"] == name and math.isfinite(cf):
                r["graded_mm"] = cf
    best = starts[0]
    if len(starts) > 1:  # the runner-up must be closer by more than two drapes of one pattern differ
        from unsew.fit.material import CHECK_MARGIN_MM, CHECK_MARGIN_REL  # here: material imports this module

        cf0, cf1 = starts[0][0], starts[1][0]
        if math.isfinite(cf1) and (
            not math.isfinite(cf0) or cf1 < cf0 - max(CHECK_MARGIN_MM, CHECK_MARGIN_REL * cf0)
        ):
            best = starts[1]
        scene.log(
            "base tie: graded " + ", ".join(f"{n} {cf:.2f} mm" for cf, n, _ in starts) + f"; {best[1]} kept"
        )
        table.sort(key=lambda r: r["base"] != best[1])
    return best[2].replace(base_name=best[1], base_choice=tuple(table))


def _check_contours_compatible(n_src: int, n_tgt: int, garment: str) -> None:
    if n_tgt == 0:
        raise InputError(
            "the target has no open contours (hem, cuff, neckline): it does not look like a garment"
        )
    if n_src and abs(n_src - n_tgt) > max(2, n_src // 2):
        raise InputError(
            f"the base pattern's garment has {n_src} openings but the target has {n_tgt}: "
            f"the base ({garment or 'custom'}) does not match this target's garment type"
        )


def start(
    base,
    scene: Scene,
    material,
    *,
    label: str = "drape base",
    garment: str = "",
    base_from: tuple | None = None,
    log: Callable[[str], None] | None = None,
) -> Start:
    """Dress ``base`` on ``scene.body`` in ``material`` and, unless ``scene.cfg.grading`` is off,
    grade it to ``scene.target`` in the same material (:func:`unsew.grading.grade.grade`). Raises
    InputError when the base's openings do not match the target's (``garment`` names the base in
    the message).

    base_from: (mesh, x) the base already dressed in another material: then, when
    WARM_STEPS > 0, the base drape is settled from it (:func:`unsew.dress.settle`)
    instead of dressed from scratch. log: where grading's one-line warnings go (None: nowhere)."""
    cfg, target = scene.cfg, scene.target
    mesh_b, x_b, dress_s = _base_drape(base, scene, material, label, base_from)
    _check_contours_compatible(len(open_contours(x_b, mesh_b.faces)), len(target.contours), garment)
    if not cfg.grading:
        anchors = held_anchors(base, mesh_b, scene.body, scene.sdf, x_b)
        return Start(base, base, mesh_b, x_b, [], x_b, mesh_b, material, dress_s=dress_s, anchors=anchors)

    # grading reads lengths and girths off its drapes: an unsound one is not dressed again with
    # the edges repelled (docs/decisions/042)
    grade_drape = cfg.drape.replace(edge_fallback=False)

    def drape_fn(p, m, b):
        return dress(p, b, sdf=scene.sdf, mesh=m, material=material, settings=grade_drape).x.numpy()

    settings = GradingSettings(
        drape=cfg.drape,
        material=material,
        area=target.area if cfg.area == "target" else None,
        side_seams=cfg.side_seams,
        band_gap=cfg.band_gap,
        room=_grading_room(scene.budget) if isinstance(scene, FitContext) else None,
    )
    g = grade(
        base, scene.body, target.verts, target.faces, settings, mesh=mesh_b, x_init=x_b, drape_fn=drape_fn
    )
    if g.note and log is not None:
        log(g.note)
    x = np.asarray(g.x_draped)
    astray = graded_astray(target.distance_mm(x_b, mesh_b.faces), target.distance_mm(x, g.mesh.faces))
    if astray:
        if log is not None:
            log(f"grading refused: {astray}; phase two starts from the base")
        anchors = held_anchors(base, mesh_b, scene.body, scene.sdf, x_b)
        table = _refused_table(g.table, f"refused, none of these edits kept ({astray})")
        return Start(base, base, mesh_b, x_b, table, x_b, mesh_b, material, dress_s=dress_s, anchors=anchors)
    anchors = held_anchors(g.pattern, g.mesh, scene.body, scene.sdf, x)
    return Start(base, g.pattern, g.mesh, x, g.table, x_b, mesh_b, material, dress_s=dress_s, anchors=anchors)


def _grading_room(budget) -> Callable[[float, str], bool]:
    """Grading's ``room`` (:class:`~unsew.grading.grade.GradingSettings`) under a fit's time limit
    (:mod:`unsew.fit.budget`; a :class:`Scene` that is not a fit's has none): a drape grading can
    do without runs when it (estimated at ``seconds``, the last graded drape's) still ends in
    time; otherwise ``what`` is recorded as cut. Nothing after grading is reserved for: all that
    follows gives way in its turn, and a fit whose phase two does not run returns the graded
    drape without dressing it again."""

    def may_drape(seconds: float, what: str) -> bool:
        if budget.fits(seconds):
            return True
        budget.cut(f"{what} (about {seconds:.0f} s a drape: it would overrun)")
        return False

    return may_drape


def _refused_table(table: list, why: str) -> list:
    """Grading's contour rows with ``why`` added to the first row's warnings (the report's
    "grading:" notes): the rows say what grading tried, not what the start holds."""
    rows = [dict(r) for r in table]
    if rows:
        rows[0]["warnings"] = list(rows[0].get("warnings") or []) + [why]
    return rows


def graded_astray(base_mm: float, graded_mm: float) -> str:
    """Why a graded drape ``graded_mm`` [mm] from the target is refused against its base's
    ``base_mm`` [mm] (:data:`GRADING_ASTRAY`, :data:`GRADING_ASTRAY_MM`); "" when it is kept. A
    graded drape whose distance is not finite is refused when the base's is."""
    if not math.isfinite(base_mm):
        return ""
    if not math.isfinite(graded_mm):
        return f"its drape's distance to the target is not finite (the base's: {base_mm:.1f} mm)"
    if graded_mm > GRADING_ASTRAY * base_mm and graded_mm > base_mm + GRADING_ASTRAY_MM:
        return f"its drape lies {graded_mm:.1f} mm from the target, the base's {base_mm:.1f} mm"
    return ""


def _base_drape(base, scene: Scene, material, label: str, base_from: tuple | None):
    """(mesh, drape (n_x, 3) [m], seconds a drape from scratch took, 0 when settled): ``base``
    dressed from scratch in ``material``, or settled WARM_STEPS steps from ``base_from``."""
    t0, dress_s = time.perf_counter(), 0.0
    with scene.progress.phase(label) as bar:
        if base_from is not None and WARM_STEPS > 0:
            mesh_b = base_from[0]
            x_b = settle(
                mesh_b,
                base_from[1],
                scene.sdf,
                material,
                settings=scene.cfg.drape.replace(settle_steps=WARM_STEPS),
                progress=bar,
                anchors=held_anchors(base, mesh_b, scene.body, scene.sdf, base_from[1]),
            )
        else:
            dressed = dress(
                base, scene.body, sdf=scene.sdf, material=material, settings=scene.cfg.drape, progress=bar
            )
            mesh_b, x_b = dressed.mesh, dressed.x.numpy().copy()
            dress_s = time.perf_counter() - t0
    return mesh_b, x_b, dress_s
