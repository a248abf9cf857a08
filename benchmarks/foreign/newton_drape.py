"""Drape a meshed sewing pattern on a body with NVIDIA newton's Style3D cloth solver (CPU).

The independent simulator of the foreign benchmark: nothing of unsew's simulator is used. unsew
only supplies the panel mesh (unsew.meshing) and the panels' start positions around the body
(unsew.body.placement).

Two phases:
1. sewing, gravity off: the unsewn panels (one particle per 2D rest vertex) with a zero-length
   spring (``seam_spring_n_m``, an external force evaluated at the start of each substep)
   between every stitched vertex pair, velocities damped by ``sew_damping`` per substep, the
   body's friction ``sew_contact_mu``; no gravity, so nothing needs holding;
2. drape: the sewn mesh (stitched vertices merged at their mean) rebuilt as one cloth, gravity
   ramped in over ``ramp_frames`` frames with the waist line of a lower garment held still
   until ``hold_frames`` (counted from the start), then released and settled.

Optionally (``attach``) some vertices are kept at given heights in both phases: their height
reset before each substep, and in the drape put on the body and made heavier (drape_newton).

World frame: metres, Y up (FORMATS.md); newton runs Z up: (x, y, z) -> (x, -z, y) and back.
"""

from __future__ import annotations

import time

import numpy as np

#: Settings (shared/STACK.md's newton trial): recorded in each case's meta.json.
SETTINGS = dict(
    fps=60,
    substeps=4,
    iterations=10,
    linear_iterations=10,
    density_kg_m2=0.2,
    tri_aniso_ke=[2.0e3, 2.0e3, 2.0e2],
    edge_aniso_ke=[2.0e-5, 1.0e-5, 5.0e-6],
    particle_radius_m=0.004,
    soft_contact_ke=1.0e3,
    soft_contact_kd=1.0e-3,
    soft_contact_mu=0.5,
    sew_contact_mu=0.5,
    sew_frames=40,
    seam_spring_n_m=30.0,
    seam_force_max_n=float("inf"),
    sew_damping=0.05,
    sew_speed_max_m_s=float("inf"),
    ramp_frames=15,
    hold_frames=55,
    settle_frames=90,
    hold_band_m=0.02,
    attach_clearance_m=0.01,
    attach_mass_factor=1.0e4,
    ground=True,
    self_contact=1.0,  # 0: the cloth's contact with itself off (Style3D vertex-face, edge-edge)
)


#: Retried in order when a drape diverges (a sewing force that one garment needs blows another
#: up where several seams meet at a light corner vertex): the used one is recorded per case.
FALLBACKS = [
    {},
    {"seam_force_max_n": 1.0, "sew_speed_max_m_s": 0.5},
]


#: A vertex farther than this from the body's bounding-box centre means the drape blew up [m].
MAX_REACH = 1.5


def _to_z(p):
    p = np.asarray(p, np.float64)
    return np.stack([p[:, 0], -p[:, 2], p[:, 1]], axis=1)


def _to_y(p):
    p = np.asarray(p, np.float64)
    return np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1)


def _model(x_z, tris3d, uv, tris_uv, body_v_z, body_f, s):
    import newton
    import warp as wp
    from newton.solvers import style3d

    builder = newton.ModelBuilder(up_axis=newton.Axis.Z)
    newton.solvers.SolverStyle3D.register_custom_attributes(builder)
    style3d.add_cloth_mesh(
        builder,
        pos=wp.vec3(0.0, 0.0, 0.0),
        rot=wp.quat_identity(),
        vel=wp.vec3(0.0, 0.0, 0.0),
        vertices=x_z.tolist(),
        indices=np.asarray(tris3d).ravel().tolist(),
        panel_verts=np.asarray(uv).tolist(),
        panel_indices=np.asarray(tris_uv).ravel().tolist(),
        density=s["density_kg_m2"],
        particle_radius=s["particle_radius_m"],
        tri_aniso_ke=wp.vec3(*s["tri_aniso_ke"]),
        edge_aniso_ke=wp.vec3(*s["edge_aniso_ke"]),
    )
    builder.add_shape_mesh(
        body=-1, mesh=newton.Mesh(body_v_z.astype(np.float32), np.asarray(body_f).ravel().astype(np.int32))
    )
    if s["ground"]:  # the body stands on the ground (its lowest point): cloth reaching it rests on it
        builder.add_ground_plane(height=float(body_v_z[:, 2].min()))
    model = builder.finalize(device="cpu")
    model.soft_contact_ke = s["soft_contact_ke"]
    model.soft_contact_kd = s["soft_contact_kd"]
    model.soft_contact_mu = s["soft_contact_mu"]
    return model


def _set_active(model, held: np.ndarray, active: bool):
    import newton
    import warp as wp

    flags = model.particle_flags.numpy()
    if active:
        flags[held] |= int(newton.ParticleFlags.ACTIVE)
    else:
        flags[held] &= ~int(newton.ParticleFlags.ACTIVE)
    model.particle_flags = wp.array(flags, dtype=model.particle_flags.dtype, device="cpu")


class _Runner:
    """Runs a newton model for a number of frames under the settings ``s`` (SETTINGS' keys),
    raising when a vertex leaves the body's neighbourhood (MAX_REACH from ``centre``)."""

    def __init__(self, s: dict, centre):
        import newton

        self.s, self.centre = s, centre
        self.dt = 1.0 / s["fps"] / s["substeps"]
        self.solver_cfg = newton.solvers.SolverStyle3D.Config(
            iterations=s["iterations"], linear_iterations=s["linear_iterations"]
        )

    def run(self, model, x0, frames, gravity_of_frame, held, hook=None, until=None):
        """Positions (n, 3) [m, Y up] after ``frames`` frames from x0 at rest; gravity_of_frame(f)
        -> (gravity factor, release the held vertices now); hook(state) before each substep;
        until(f, q_before, q_after) (positions Z up, float32) True ends the run after frame f."""
        import newton
        import warp as wp

        s = self.s
        state0, state1 = model.state(), model.state()
        state0.particle_q.assign(wp.array(_to_z(x0).astype(np.float32), dtype=wp.vec3, device="cpu"))
        state0.particle_qd.zero_()
        control = model.control()
        solver = newton.solvers.SolverStyle3D(model, config=self.solver_cfg)
        if not s.get("self_contact", 1.0):  # the body's contact stays (the same Collision object's)
            solver.collision.stiff_vf = solver.collision.stiff_ee = solver.collision.stiff_ef = 0.0
        pipeline = newton.CollisionPipeline(model, soft_contact_margin=0.01)
        contacts = pipeline.contacts()
        if len(held):
            _set_active(model, held, False)
        for f in range(frames):
            g, release = gravity_of_frame(f)
            if release and len(held):
                _set_active(model, held, True)
                held = np.zeros(0, np.int64)
            model.set_gravity((0.0, 0.0, -9.81 * g))
            pipeline.collide(state0, contacts)
            q_before = state0.particle_q.numpy().copy() if until is not None else None
            for _ in range(s["substeps"]):
                state0.clear_forces()
                if hook is not None:
                    hook(state0)
                solver.step(state0, state1, control, contacts, self.dt)
                state0, state1 = state1, state0
            q = state0.particle_q.numpy()
            far = np.abs(q - self.centre).max() if np.isfinite(q).all() else np.inf
            if far > MAX_REACH:
                raise RuntimeError(
                    f"newton diverged at frame {f} (a vertex {far:.1f} m from the body's centre)"
                )
            if until is not None and until(f, q_before, q):
                break
        return _to_y(state0.particle_q.numpy())


def _seam_pull(sp, s: dict, guide=None):
    """The sewing phase's hook: spring forces pulling each seam pair together (capped), and
    damped, capped velocities. ``guide``: (uv indices (k,) int64, points (k, 3) [m, Y up]) each
    pulled towards its point by a spring of the same stiffness, or None."""
    import warp as wp

    if guide is not None and len(guide[0]):
        gi, gp = np.asarray(guide[0], np.int64), _to_z(guide[1])
    else:
        gi, gp = np.zeros(0, np.int64), np.zeros((0, 3))

    def pull(state):
        q = state.particle_q.numpy()
        d = (q[sp[:, 1]] - q[sp[:, 0]]).astype(np.float64)
        f = np.zeros((len(q), 3))
        np.add.at(f, sp[:, 0], s["seam_spring_n_m"] * d)
        np.add.at(f, sp[:, 1], -s["seam_spring_n_m"] * d)
        np.add.at(f, gi, s["seam_spring_n_m"] * (gp - q[gi]))
        fn = np.linalg.norm(f, axis=1, keepdims=True)
        f *= np.minimum(1.0, s["seam_force_max_n"] / np.maximum(fn, 1e-12))
        state.particle_f.assign(wp.array(f.astype(np.float32), dtype=wp.vec3, device="cpu"))
        v = state.particle_qd.numpy() * (1.0 - s["sew_damping"])
        vn = np.linalg.norm(v, axis=1, keepdims=True)
        v *= np.minimum(1.0, s["sew_speed_max_m_s"] / np.maximum(vn, 1e-12))
        state.particle_qd.assign(wp.array(v.astype(np.float32), dtype=wp.vec3, device="cpu"))

    return pull


def _attach(idx, height, then=None, damp=0.0):
    """A hook holding the particles ``idx`` (k,) at the heights ``height`` (k,) [m] (their
    vertical position set and vertical velocity zeroed before each substep, their velocity
    across damped by ``damp`` per substep), after running the hook ``then`` (or nothing)."""
    import warp as wp

    idx = np.asarray(idx, np.int64)
    height = np.asarray(height, np.float64)

    def hold(state):
        if then is not None:
            then(state)
        if not len(idx):
            return
        q = state.particle_q.numpy()
        q[idx, 2] = height
        state.particle_q.assign(wp.array(q, dtype=wp.vec3, device="cpu"))
        v = state.particle_qd.numpy()
        v[idx] *= 1.0 - damp
        v[idx, 2] = 0.0
        state.particle_qd.assign(wp.array(v, dtype=wp.vec3, device="cpu"))

    return hold


def on_body(p: np.ndarray, body_v: np.ndarray, body_f: np.ndarray, clearance: float) -> np.ndarray:
    """Points p (k, 3) [m, Y up] moved horizontally onto the body: along the ray from the body's
    vertical axis (its bounding-box centre in x and z) at each point's height towards the point,
    to the ray's first exit through the body's surface plus ``clearance`` [m]; a point whose
    axis point lies outside the body (between the legs) is kept."""
    import trimesh

    v = np.asarray(body_v, np.float64)
    c = 0.5 * (v.min(axis=0) + v.max(axis=0))
    origin = np.c_[np.full(len(p), c[0]), p[:, 1], np.full(len(p), c[2])]
    d = p - origin
    d[:, 1] = 0.0
    d /= np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-9)
    tm = trimesh.Trimesh(v, body_f, process=False)
    out = np.array(p, np.float64)
    k = np.flatnonzero(tm.contains(origin))
    if len(k):
        hit, ray, _ = tm.ray.intersects_location(origin[k], d[k], multiple_hits=False)
        out[k[ray]] = hit + clearance * d[k[ray]]
    return out


def _weigh(model, idx, factor: float) -> None:
    """Multiply the masses of the model's particles ``idx`` by ``factor``: within a step a heavy
    particle barely moves under the cloth's pull, across many it still follows it."""
    import warp as wp

    m = model.particle_mass.numpy().copy()
    m[idx] *= factor
    model.particle_mass = wp.array(m, dtype=model.particle_mass.dtype, device="cpu")
    inv = model.particle_inv_mass.numpy().copy()
    inv[idx] /= factor
    model.particle_inv_mass = wp.array(inv, dtype=model.particle_inv_mass.dtype, device="cpu")


def _sew(mesh, x_u, body, runner: _Runner, info: dict, log, attach=None, guide=None):
    """Phase 1: sew the unsewn panels x_u (Nu, 3) [m] on body = (bz, body_f), the uv vertices
    ``attach[0]`` held at the heights ``attach[1]`` [m] (or none), the uv vertices ``guide[0]``
    pulled towards the points ``guide[1]`` (or none, see :func:`_seam_pull`); returns the unsewn
    positions after sewing, and records the seam gaps and time in ``info``."""
    s = runner.s
    t0 = time.time()
    sp = np.asarray(mesh.seam_pairs)
    m1 = _model(
        _to_z(x_u),
        mesh.faces_uv,
        mesh.uv,
        mesh.faces_uv,
        *body,
        {**s, "soft_contact_mu": s["sew_contact_mu"]},
    )
    hook = _seam_pull(sp, s, guide)
    if attach is not None:
        hook = _attach(attach[0], attach[1], then=hook)
    x1 = runner.run(m1, x_u, s["sew_frames"], lambda f: (0.0, False), np.zeros(0, np.int64), hook=hook)
    gaps = np.linalg.norm(x1[sp[:, 0]] - x1[sp[:, 1]], axis=1) if len(sp) else np.zeros(1)
    info["gap_after_sewing_m"] = float(gaps.max())
    info["gap_after_sewing_p95_m"] = float(np.percentile(gaps, 95))
    if len(sp):
        w = int(np.argmax(gaps))
        pn = [mesh.panel_names[int(mesh.uv_panel[k])] for k in sp[w]]
        log(f"  widest seam gap between {pn[0]} and {pn[1]} at y {x1[sp[w, 0], 1]:.3f} m")
    info["sew_s"] = time.time() - t0
    log(
        f"  sewing: {s['sew_frames']} frames {info['sew_s']:.0f} s, largest seam gap "
        f"{info['gap_after_sewing_m'] * 1000:.1f} mm"
    )
    return x1


def drape_newton(mesh, x_unsewn, body_v, body_f, *, lower: bool, settings=None, log=print, holds=None):
    """Sew and drape ``mesh`` (unsew GarmentMesh) from its unsewn start ``x_unsewn`` (Nu, 3) [m]
    on the body (body_v (V, 3) [m], body_f (F, 3)). ``lower``: hold the waist (skirts,
    trousers). ``holds``: a dict with any of ``attach`` and ``guide``, or None.
    ``attach``: (uv indices (k,) int64, heights (k,) [m]) held at those heights
    while sewing and draping (free across), put on the body at those heights (:func:`on_body`)
    when the drape starts and made ``attach_mass_factor`` times heavier there, so that the
    cloth's pull cannot move them far within a step (uv vertices sewn together must share a
    height). ``guide``: (uv indices (k,) int64, points (k, 3) [m]) pulled towards those points
    while sewing (:func:`_seam_pull`).
    Returns (x (n_x, 3) float64 [m] sewn vertices in the world frame, info dict with per-phase
    timings [s], the largest seam gap after sewing [m] and frames run)."""
    import warp as wp

    wp.config.quiet = True
    attach, guide = (holds or {}).get("attach"), (holds or {}).get("guide")
    s = dict(SETTINGS if settings is None else settings)
    bz = _to_z(body_v)
    runner = _Runner(s, 0.5 * (bz.min(axis=0) + bz.max(axis=0)))
    info = {}

    # held: the waist line of a lower garment (vertices within hold_band of its top)
    x_u = np.asarray(x_unsewn, np.float64)
    held_u = (
        np.flatnonzero(x_u[:, 1] > x_u[:, 1].max() - s["hold_band_m"]) if lower else np.zeros(0, np.int64)
    )
    x1 = _sew(mesh, x_u, (bz, body_f), runner, info, log, attach, guide)

    # phase 2: the sewn garment
    t0 = time.time()
    n_x = int(mesh.n_x)
    xs = np.zeros((n_x, 3))
    cnt = np.zeros(n_x)
    np.add.at(xs, mesh.x_of_u, x1)
    np.add.at(cnt, mesh.x_of_u, 1.0)
    xs /= cnt[:, None]
    held_x = np.unique(np.asarray(mesh.x_of_u)[held_u]) if len(held_u) else np.zeros(0, np.int64)
    m2 = _model(_to_z(xs), mesh.faces, mesh.uv, mesh.faces_uv, bz, body_f, s)
    ramp, hold = s["ramp_frames"], s["hold_frames"] - s["sew_frames"]
    frames = max(ramp, hold) + s["settle_frames"]
    hook = None
    if attach is not None and len(attach[0]):  # on the body at their heights, weighted, held up
        ax, first = np.unique(np.asarray(mesh.x_of_u)[np.asarray(attach[0], np.int64)], return_index=True)
        h = np.asarray(attach[1], np.float64)[first]
        xs[ax, 1] = h
        xs[ax] = on_body(xs[ax], body_v, body_f, s["attach_clearance_m"])
        _weigh(m2, ax, s["attach_mass_factor"])
        hook = _attach(ax, h, damp=s["sew_damping"])
    x2 = runner.run(m2, xs, frames, lambda f: (min(1.0, (f + 1) / ramp), f == hold), held_x, hook=hook)
    info["drape_s"] = time.time() - t0
    info["frames"] = s["sew_frames"] + frames
    log(f"  drape: {frames} frames {info['drape_s']:.0f} s")
    return x2, info


#: Settling a finished drape until it is at rest (:func:`settle_newton`): newton's cloth at the
#: drape's 10 solver iterations reads 58 times its bending rigidity after 150 frames and settles
#: only after about 2400; at 40 it settles within 600 (docs/decisions/031).
SETTLE = dict(iterations=40, linear_iterations=40, frames_max=600, check_every=30, rest_speed_m_s=0.005)


def settle_newton(mesh, x, body_v, body_f, *, settings, attach=None, settle=None, log=print):
    """A finished drape x (n_x, 3) [m, Y up] of ``mesh`` run on under full gravity with the
    solver's iterations of ``settle`` (SETTLE's keys) until at rest: every ``check_every`` frames,
    the 99th percentile of the vertices' speeds over the last frame below ``rest_speed_m_s``, or
    ``frames_max`` frames. ``settings``: the drape's (SETTINGS' keys); ``attach``: sewn vertex
    indices (k,) int64 held at their heights in x, weighted as the drape weighted them (or None).
    Returns (x (n_x, 3) float64 [m], info: frames run, seconds, the speeds' 99th percentile and
    largest [m/s] at the end, at rest or not)."""
    import warp as wp

    wp.config.quiet = True
    c = {**SETTLE, **(settle or {})}
    s = {**settings, "iterations": c["iterations"], "linear_iterations": c["linear_iterations"]}
    bz = _to_z(body_v)
    runner = _Runner(s, 0.5 * (bz.min(axis=0) + bz.max(axis=0)))
    x = np.asarray(x, np.float64)
    model = _model(_to_z(x), mesh.faces, mesh.uv, mesh.faces_uv, bz, body_f, s)
    hook = None
    free = np.ones(len(x), bool)
    if attach is not None and len(attach):
        ax = np.unique(np.asarray(attach, np.int64))
        _weigh(model, ax, s["attach_mass_factor"])
        hook = _attach(ax, x[ax, 1], damp=s["sew_damping"])
        free[ax] = False
    info = {"frames": 0, "at_rest": False}

    def until(f, q0, q1):
        info["frames"] = f + 1
        if (f + 1) % c["check_every"]:
            return False
        v = np.linalg.norm((q1 - q0)[free], axis=1) * s["fps"]
        info["speed_p99_m_s"], info["speed_max_m_s"] = float(np.percentile(v, 99)), float(v.max())
        info["at_rest"] = info["speed_p99_m_s"] < c["rest_speed_m_s"]
        log(f"  settle: frame {f + 1}, speed p99 {info['speed_p99_m_s'] * 1000:.1f} mm/s")
        return info["at_rest"]

    t0 = time.time()
    x2 = runner.run(model, x, c["frames_max"], lambda f: (1.0, False), np.zeros(0, np.int64), hook, until)
    info["seconds"] = round(time.time() - t0, 1)
    return x2, info
