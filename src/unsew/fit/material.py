"""The starting material of phase two (``material.start: auto``, a step the paper leaves to the
user): grade in cotton, drape the graded pattern in every library fabric (:func:`choose_material`),
grade again in the closest others, then search the winner's stretch and bending scale by draping
(:func:`refine_material`). Phase two starts from the closest of these drapes by mean surface
distance, unless the winner, dressed from scratch, lies clearly farther than the pattern graded
in cotton (:data:`CHECK_CHOICE`, :func:`_checked`). Its hand-off is a :class:`MaterialChoice`.

Each candidate is let settle (:data:`~unsew.fit.start.WARM_STEPS` steps, :func:`unsew.dress.settle`) from the
drape it competes with, the pattern already sewn, instead of being dressed from scratch (placement,
sewing and settling), on one SimModel of the start's mesh (docs/decisions/002)."""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Callable

from unsew._memory import release_free_memory
from unsew.dress import dress, held_anchors, settle
from unsew.errors import InputError
from unsew.fit.budget import TimeBudget
from unsew.fit.config import material_candidates
from unsew.fit.progress import Progress
from unsew.fit.scene import Scene
from unsew.fit.start import WARM_STEPS, Start, start
from unsew.sim.checks import check_drape, check_dressed
from unsew.sim.material import get_material
from unsew.sim.model import SimModel

__all__ = [
    "MaterialChoice",
    "choose_start",
    "choose_material",
    "refine_material",
    "AUTO_START_MATERIAL",
    "REFINE_GROUPS",
]

#: the material ``material.start: auto`` drapes the base and grades in, before it chooses
AUTO_START_MATERIAL = "cotton"
#: The material check (:func:`_checked`) falls back to the cotton-graded start only when the chosen
#: fabric's drape from scratch lies farther than it by more than this [mm] and this share of it [-].
CHECK_MARGIN_MM = 0.5
CHECK_MARGIN_REL = 0.1
#: The groups of Gamma that :func:`refine_material` scales together: name -> Material fields.
REFINE_GROUPS = {"stretch": ("h00", "h01", "h11", "h22"), "bending": ("bend",)}
#: ``material.start: auto``: how many of the best candidates other than cotton are graded again in
#: their own fabric [-]
REGRADE = 2
#: ``material.start: auto``: rounds of the stiffness search after the choice (stretch and bending
#: scaled by 1/s and s, s = 2, sqrt 2, ...); 0: off [-]
REFINE_ROUNDS = 2
#: ``material.start: auto``: a scaling that lowers the distance is applied again, up to this many
#: more times in a row, while it keeps lowering it (a target far stiffer or softer than every
#: library fabric is reached in one round; docs/decisions/040) [-]
REFINE_REPEAT = 3
#: ``material.start: auto``: the chosen pattern and fabric dressed from scratch; clearly farther
#: (CHECK_MARGIN_MM and CHECK_MARGIN_REL) than the cotton-graded pattern: start from that one
#: (:func:`_checked`)
CHECK_CHOICE = True


@dataclass(frozen=True)
class MaterialChoice:
    """Phase two's start: ``start`` (pattern, mesh, drape; ``start.material`` the fabric) and the
    choice's table: rows {"material", "chamfer_mm", "pattern"}, best first, after the material
    check's two drapes from scratch (the kept start first) when it ran (empty when the material
    was given)."""

    start: Start
    table: list = field(default_factory=list)
    seconds: float = 0.0  #: time the choice took [s]


def choose_material(names, dress_in, objective, *, progress: Progress | None = None, room=None):
    """The library material whose drape of the graded pattern lies closest to the target.

    names: library material names; dress_in(material, bar, x_from) -> (Nx, 3) drape [m] of the
    graded pattern in that material (settled from ``x_from``, or from the pattern's own drape when
    None, or dressed from scratch: :func:`_dresser`); objective(x) -> its distance to the target
    [mm]; room(seconds) -> False stops the choice before the next material (the fit's time limit;
    seconds: the last drape's duration [s]), the ones draped so far competing.
    Returns (Material, drape of the winner, table): the table lists every finite candidate,
    best first, as {"material", "chamfer_mm"}.
    """
    progress = progress or Progress(False)
    rows, drapes, last_s = [], {}, None
    for name in names:
        if last_s is not None and room is not None and not room(last_s):
            break
        t0 = time.perf_counter()
        with progress.phase(f"material {name}") as bar:
            x = dress_in(get_material(name), bar)
        last_s = time.perf_counter() - t0
        loss = objective(x)
        if not math.isfinite(loss):
            continue
        drapes[name] = x
        rows.append({"material": name, "chamfer_mm": loss})
    if not rows:
        raise InputError(
            "no library material gave a finite drape of the graded pattern; pass --material NAME"
        )
    rows.sort(key=lambda r: r["chamfer_mm"])
    best = rows[0]["material"]
    return get_material(best), drapes[best], rows


def refine_material(
    material,
    label: str,
    x0,
    cf0: float,
    dress_in,
    objective,
    *,
    progress: Progress | None = None,
    keep_going: Callable[[], bool] | None = None,
):
    """Coordinate search on the chosen fabric's stiffness, by draping: scale the stretch entries
    (H00, H01, H11, H22 together, so the Poisson ratio stays) and then the bending stiffness by
    1/s and s, s = 2, then sqrt(2), ... (:data:`REFINE_ROUNDS` steps), and keep a scaling when the
    pattern, draped in it, lies closer to the target; a kept scaling is tried again, up to
    :data:`REFINE_REPEAT` more times, while it keeps getting closer.

    material: the start (unsew.sim.material.Material) named ``label`` in the table; x0, cf0: its
    drape (Nx, 3) [m] and distance [mm]; dress_in, objective as for :func:`choose_material` (each
    scaling is draped from the best drape so far); keep_going() -> False stops the search before
    the next scaling (the fit's time limit).
    Returns (Material, drape, rows): rows list every scaling tried, {"material", "chamfer_mm"}.
    """
    walk = _Walk(material, label, x0, cf0, dress_in, objective, progress or Progress(False), keep_going)
    for r in range(REFINE_ROUNDS):
        s = 2.0 ** (0.5**r)
        for group in REFINE_GROUPS:
            for f in (1.0 / s, s):
                if not walk.step(group, f):
                    continue
                for _ in range(REFINE_REPEAT):
                    if not walk.step(group, f):
                        break
                break  # the other direction cannot be better too on a unimodal distance
            if walk.stopped:
                return walk.best, walk.x_best, walk.rows
    return walk.best, walk.x_best, walk.rows


@dataclass
class _Walk:
    """The state of :func:`refine_material`'s search: the best fabric, its drape and distance,
    the scale of each group against the start, the rows tried, and whether the time ran out."""

    best: object
    label: str
    x_best: object
    cf_best: float
    dress_in: Callable
    objective: Callable
    progress: Progress
    keep_going: Callable[[], bool] | None
    rows: list = field(default_factory=list)
    scale: dict = field(default_factory=lambda: {g: 1.0 for g in REFINE_GROUPS})
    stopped: bool = False

    def step(self, group: str, f: float) -> bool:
        """Drape the best fabric with ``group`` scaled by f; True (and kept) when it lies closer."""
        if self.stopped or (self.keep_going is not None and not self.keep_going()):
            self.stopped = True
            return False
        cand = dataclasses.replace(self.best, **{k: getattr(self.best, k) * f for k in REFINE_GROUPS[group]})
        with self.progress.phase(f"{group} x{self.scale[group] * f:.2g}") as bar:
            x = self.dress_in(cand, bar, self.x_best)
        cf = self.objective(x)
        tag = ", ".join(f"{g} x{self.scale[g] * (f if g == group else 1.0):.2g}" for g in REFINE_GROUPS)
        if math.isfinite(cf):
            self.rows.append({"material": f"{self.label} ({tag})", "chamfer_mm": cf})
        if not cf < self.cf_best:
            return False
        self.best, self.x_best, self.cf_best = cand, x, cf
        self.scale[group] *= f
        return True


def _dresser(s: Start, scene: Scene):
    """dress_in(material, bar, x_from=None) -> drape (Nx, 3) [m] of the start's pattern in
    ``material``: settled WARM_STEPS steps from ``x_from`` (default ``s.x``), or,
    when warm_steps is 0, dressed from scratch (x_from unused)."""

    model = SimModel.build(s.mesh.faces, s.mesh.faces_uv) if WARM_STEPS > 0 else None

    def dress_in(material, bar=None, x_from=None):
        if model is not None:
            x = settle(
                s.mesh,
                s.x if x_from is None else x_from,
                scene.sdf,
                material,
                settings=scene.cfg.drape.replace(settle_steps=WARM_STEPS),
                model=model,
                progress=bar,
                anchors=s.anchors,
            )
        else:
            x = dress(
                s.graded,
                scene.body,
                sdf=scene.sdf,
                mesh=s.mesh,
                material=material,
                settings=scene.cfg.drape,
                progress=bar,
            ).x.numpy()
        release_free_memory()  # the drape's scratch memory (unsew._memory)
        return x

    return dress_in


@dataclass
class _Room:
    """Whether the material choice drapes the next fabric (``room(seconds)``, the last drape's
    duration): while it and the check's drape from scratch (``check_s`` [s]) still end within the
    budget, or, past it (``rescue``: the graded drape fails a result's checks), until a fabric's
    drape (``seen``) passes them: another fabric is then the fit's only way to a sound result, and
    the first sound one ends the need. mesh: the graded pattern's GarmentMesh; scene: the fit's."""

    budget: TimeBudget
    check_s: float
    mesh: object
    scene: Scene
    rescue: bool = False
    mended: bool = False

    def verdict(self, x):
        """:func:`~unsew.sim.checks.check_drape` of a drape x (Nx, 3) [m] of the graded pattern."""
        m, sc = self.mesh, self.scene
        return check_drape(x, faces=m.faces, uv=m.uv, faces_uv=m.faces_uv, body=sc.body, sdf=sc.sdf)

    def seen(self, x) -> None:
        if self.rescue and not self.mended:
            self.mended = self.verdict(x).ok

    def __call__(self, next_s: float) -> bool:
        if (self.rescue and not self.mended) or self.budget.fits(next_s + self.check_s):
            return True
        self.budget.cut("material choice: the other fabrics not draped (they would overrun)")
        return False


def choose_start(
    first: Start, scene: Scene, *, garment: str = "", budget: TimeBudget | None = None
) -> MaterialChoice:
    """The material stage: ``first`` unchanged when ``scene.cfg.material.start`` names a material,
    else the auto choice (module docstring) starting from ``first`` (graded in cotton). With a
    ``budget``, the grading in other fabrics and the stiffness search stop once half its limit is
    spent, and the fabrics are draped only while each (timed as the one before) and the check's drape
    from scratch (``first.dress_s``) still end in time (:mod:`unsew.fit.budget`), unless ``first``'s
    drape fails the checks a result passes (:func:`~unsew.sim.checks.check_drape`): the fabrics
    are then draped until one drapes soundly (:class:`_Room`)."""
    budget = budget or TimeBudget(0)
    if scene.cfg.material.start != "auto":
        return MaterialChoice(first)
    # each fabric's settle and, after them, the check's drape from scratch must end in time
    check_s = first.dress_s if CHECK_CHOICE else 0.0
    settle_s = first.dress_s * WARM_STEPS / max(scene.cfg.drape.sew_steps + scene.cfg.drape.settle_steps, 1)
    room = _Room(budget, check_s, first.mesh, scene)
    if not budget.fits(settle_s + check_s):
        verdict = room.verdict(first.x)
        if verdict.ok:
            budget.cut(f"material choice: {AUTO_START_MATERIAL} kept (draping the fabrics would overrun)")
            return MaterialChoice(first)
        room.rescue = True
        scene.log(
            f"material choice: made past the time limit, as the drape graded in {AUTO_START_MATERIAL} "
            f"fails its check ({verdict.reason})"
        )
    t0 = time.perf_counter()

    def objective(x, mesh=None):
        return scene.target.distance_mm(x, (mesh or first.mesh).faces)

    def fabric_objective(x):
        room.seen(x)
        return objective(x)

    mat, x, table = choose_material(
        material_candidates(scene.cfg.material.candidates),
        _dresser(first, scene),
        fabric_objective,
        progress=scene.progress,
        room=room,
    )
    for row in table:
        row["pattern"] = f"graded in {AUTO_START_MATERIAL}"
    cur, best_cf = _regraded(first, first.replace(x=x, material=mat), table, scene, garment, budget)
    table.sort(key=lambda r: r["chamfer_mm"])
    if REFINE_ROUNDS > 0:
        cur, table = _refined(cur, table, best_cf, scene, budget, lambda x: objective(x, cur.mesh))
    r0 = table[0]
    scene.log(f"material: {r0['material']} (pattern {r0['pattern']}; {r0['chamfer_mm']:.2f} mm)")
    if CHECK_CHOICE and cur is not first:
        cur, table = _checked(first, cur, table, scene)
    return MaterialChoice(cur, table, time.perf_counter() - t0)


#: Share of the fit's time limit the material choice's optional steps may start within [-].
OPTIONAL_SHARE = 0.5


def _regraded(first: Start, cur: Start, table: list, scene: Scene, garment: str, budget: TimeBudget):
    """(the closest start, its distance [mm]): ``cur`` (the cotton-graded pattern settled in the
    closest fabric, ``table[0]``) against the best REGRADE others graded again in their own fabric;
    each such grading adds its row to ``table``. Grading in cotton favours cotton (on bench_fit's
    dress in silk the cotton-graded pattern lay 4.12 mm from the target in cotton and 4.89 in
    silk): the best others are graded again in their own fabric, and compete too."""
    best_cf = table[0]["chamfer_mm"]
    others = [r["material"] for r in table if r["material"] != AUTO_START_MATERIAL]
    for name in others[:REGRADE] if scene.cfg.grading else []:
        if not budget.within(OPTIONAL_SHARE):
            budget.cut(f"material choice: not graded again in {name} (half the limit spent)")
            continue
        try:
            s = start(
                first.base,
                scene,
                get_material(name),
                label=f"grade in {name}",
                garment=garment,
                base_from=(first.mesh_base, first.x_base),
            )
        except InputError as exc:
            scene.log(f"material {name}: grading in it failed ({exc}); left out")
            continue
        cf = scene.target.distance_mm(s.x, s.mesh.faces)
        if not math.isfinite(cf):
            continue
        table.append({"material": name, "chamfer_mm": cf, "pattern": f"graded in {name}"})
        if cf < best_cf:
            best_cf = cf
            cur = cur.replace(  # the anchors index this start's own mesh
                graded=s.graded,
                mesh=s.mesh,
                x=s.x,
                grade_table=s.grade_table,
                material=s.material,
                anchors=s.anchors,
            )
    return cur, best_cf


def _refined(cur: Start, table: list, best_cf: float, scene: Scene, budget: TimeBudget, objective):
    """(start, table): the stiffness search (:func:`refine_material`, REFINE_ROUNDS rounds) from
    ``cur`` in the best row's fabric, its rows added to ``table`` (sorted, best first); it stops
    once half the time limit is spent."""
    r0 = table[0]

    def keep_going() -> bool:
        if budget.within(OPTIONAL_SHARE):
            return True
        budget.cut("material choice: stiffness search stopped (half the limit spent)")
        return False

    mat, x, rows = refine_material(
        cur.material,
        r0["material"],
        cur.x,
        best_cf,
        _dresser(cur, scene),
        objective,
        progress=scene.progress,
        keep_going=keep_going,
    )
    table = sorted(table + [{**row, "pattern": r0["pattern"]} for row in rows], key=lambda r: r["chamfer_mm"])
    return cur.replace(x=x, material=mat), table


def _checked(first: Start, chosen: Start, table: list, scene: Scene) -> tuple[Start, list]:
    """The choice checked by a drape from scratch, as a result is judged (:data:`CHECK_CHOICE`).

    The candidates were let settle from another fabric's drape, and a settled drape can lie
    closer than the same pattern and fabric dressed from scratch (docs/decisions/002). So the chosen pattern
    is dressed from scratch in its fabric, and when that drape lies farther from the target than ``first``'s
    (graded in cotton, a drape from scratch) by more than both :data:`CHECK_MARGIN_MM` and
    :data:`CHECK_MARGIN_REL` of it (what two drapes from scratch of one pattern on two meshes differ by),
    phase two starts from ``first``; otherwise the choice stands as it was made (its settled drape). A drape
    from scratch that fails its check (:func:`unsew.sim.checks.check_dressed`: exploded, fallen, ...) gives
    way to ``first`` whatever its distance. Returns (the start, the table with the two dressed rows first,
    the kept one on top).
    """
    target = scene.target
    with scene.progress.phase("dress the chosen material") as bar:
        d = dress(
            chosen.graded,
            scene.body,
            sdf=scene.sdf,
            mesh=chosen.mesh,
            material=chosen.material,
            settings=scene.cfg.drape,
            progress=bar,
        )
    failed = check_dressed(
        d, body=scene.body
    ).reason  # exploded, fallen, ...: no start, whatever its distance
    x = d.x.numpy()
    release_free_memory()
    cf = target.distance_mm(x, chosen.mesh.faces)
    cf_first = target.distance_mm(first.x, first.mesh.faces)
    label, pattern = table[0]["material"], table[0]["pattern"]
    rows = [
        {
            "material": label,
            "chamfer_mm": cf,
            "pattern": f"{pattern}, dressed from scratch" + (f" (failed: {failed})" if failed else ""),
        },
        {
            "material": AUTO_START_MATERIAL,
            "chamfer_mm": cf_first,
            "pattern": f"graded in {AUTO_START_MATERIAL}, dressed from scratch",
        },
    ]
    keep = (
        not failed
        and math.isfinite(cf)
        and cf <= cf_first + max(CHECK_MARGIN_MM, CHECK_MARGIN_REL * cf_first)
    )
    if not keep:
        rows.reverse()
    said = f"failed ({failed})" if failed else f"lies {cf:.2f} mm from the target"
    scene.log(
        f"material check: {label} dressed from scratch {said}, the pattern graded in "
        f"{AUTO_START_MATERIAL} {cf_first:.2f} mm: phase two starts from "
        + (f"{label}" if keep else f"{AUTO_START_MATERIAL}")
    )
    return (_sound_settled(chosen, x, scene) if keep else first), rows + table


def _sound_settled(chosen: Start, x_fresh, scene: Scene) -> Start:
    """``chosen`` as it is when its settled drape passes the checks a result passes
    (:func:`unsew.sim.checks.check_drape`); else with its drape from scratch ``x_fresh`` (n_x, 3)
    [m], which passed them: a drape settled from another fabric's can keep an edge stretched
    beyond what a drape from scratch leaves, and the fit would end on it."""
    m = chosen.mesh
    verdict = check_drape(
        chosen.x, faces=m.faces, uv=m.uv, faces_uv=m.faces_uv, body=scene.body, sdf=scene.sdf
    )
    if verdict.ok:
        return chosen
    scene.log(
        f"material check: the settled drape fails its check ({verdict.reason}); its drape from scratch kept"
    )
    anchors = held_anchors(chosen.graded, m, scene.body, scene.sdf, x_fresh)
    return chosen.replace(x=x_fresh, anchors=anchors)
