"""Table-1-like benchmark of the differentiable drape (paper Table 1).

For cloth of about 1K, 2K, 3K and 8K vertices (a t-shirt once unsew.meshing and the base
pattern exist, else a square sheet) draped over a sphere: time of 1 and 20 implicit Euler steps,
forward and reverse (backprop of a loss on the final positions), peak memory of the 20-step
forward+reverse (tracemalloc-free: resident set size growth via getrusage), and the assembly of
the system matrix done by a plain per-element Python loop (the paper's baseline) versus our
static index maps. Also the linear solver backends (factor + 2 solves of the step-0 system:
cholespy, CHOLMOD with the symbolic analysis reused, simplicial and supernodal, scipy splu tuned
for SPD).

Simulator variants (--variants, "stencil:backend" pairs) are run interleaved, repeat by repeat,
so they see the same machine load: stencil "full" (exact Gauss-Newton hinge blocks, the
original) or "ring" (model.py), backend "cholespy", "cholmod" or "scipy" (solve.py; "cholmod@supernodal"
or "cholmod@simplicial" names CHOLMOD's factorization, solve.CHOLMOD_MODE), and
":unfused" for separate assembly Functions + sparse_solve instead of the fused step_solve, ":nols"
for steps without the line search on the step's incremental potential (integrator.py).

Timings on a shared 2-core machine are noisy: each figure is the minimum of --repeat runs, and the
load average is printed with every row.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_sim.py [--sizes 1000,2000,3000,8000]
        [--repeat 2] [--variants full:cholespy:unfused,ring:cholespy,ring:cholmod:unfused,ring:cholmod]
        [--no-loop]
"""

from __future__ import annotations

import argparse
import os
import resource
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402
import torch  # noqa: E402


def _mesh(n_target: int, use_tshirt: bool):
    if use_tshirt:
        try:
            from unsew.meshing import mesh_pattern
            from unsew.pattern.base import make_base_pattern

            pat = make_base_pattern("tshirt")
            el = 0.02
            for _ in range(6):
                gm = mesh_pattern(pat, edge_length=el)
                if abs(gm.n_x - n_target) / n_target < 0.15:
                    break
                el *= (gm.n_x / n_target) ** 0.5
            x0 = gm.uv_placed3d  # flat panels placed around the body, not sewn: timing only
            xs = np.zeros((gm.n_x, 3))
            xs[gm.x_of_u] = x0
            return "tshirt", gm.faces, gm.faces_uv, gm.uv, xs, gm.n_x
        except Exception as exc:  # meshing not landed yet
            print(f"(t-shirt unavailable: {type(exc).__name__}: {exc}; using square sheets)")
    from unsew.sim.meshes import grid_sheet

    k = int(round(np.sqrt(n_target))) - 1
    uv, f = grid_sheet(k, k, 0.6, 0.6)
    x = np.c_[uv[:, 0] - 0.3, np.full(len(uv), 0.105), uv[:, 1] - 0.3]
    return "sheet", f, f, uv, x, len(uv)


def _run(model, st, sdf, uv, gamma, steps, *, checkpoint, variant):
    """Seconds of a drape of ``steps`` steps forward and of its backward (loss sum |x|^2, wrt uv
    and Gamma); variant = (stencil, backend, fused, line_search)."""
    from unsew.sim import Cloth, DrapeSettings, drape

    _, name, fused, line_search = variant
    backend = _backend_mode(name)
    uvp = uv.clone().requires_grad_(True)
    gp = gamma.clone().requires_grad_(True)
    t0 = time.perf_counter()
    out = drape(
        model,
        st,
        sdf,
        Cloth(uvp, gp, 0.15),
        steps=steps,
        checkpoint=checkpoint,
        settings=DrapeSettings(backend=backend, fused=fused, line_search=line_search),
    )
    t1 = time.perf_counter()
    (out.x**2).sum().backward()
    t2 = time.perf_counter()
    return t1 - t0, t2 - t1


def _loop_assembly(model, Hm, Hb):
    """The paper's baseline: per element, per block entry, add into a dict-of-keys matrix."""
    A = {}
    faces = model.faces.tolist()
    Hm = Hm.numpy()
    for e, tri in enumerate(faces):
        for a in range(3):
            for b in range(3):
                for i in range(3):
                    for j in range(3):
                        key = (3 * tri[a] + i, 3 * tri[b] + j)
                        A[key] = A.get(key, 0.0) + Hm[e, 3 * a + i, 3 * b + j]
    hinges = model.hinges.tolist()
    Hb = Hb.numpy()
    for e, q in enumerate(hinges):
        for a in range(4):
            for b in range(4):
                for i in range(3):
                    for j in range(3):
                        key = (3 * q[a] + i, 3 * q[b] + j)
                        A[key] = A.get(key, 0.0) + Hb[e, 3 * a + i, 3 * b + j]
    return A


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1000,2000,3000,8000")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--threads", type=int, default=1, help="torch threads (the fit uses 1)")
    ap.add_argument(
        "--variants",
        default="full:cholespy:unfused,ring:cholespy,ring:cholmod:unfused,ring:cholmod",
        help="stencil:backend[:unfused][:nols],... (unfused: assembly Functions + sparse_solve instead of "
        "step_solve; nols: no line search)",
    )
    ap.add_argument("--no-loop", action="store_true", help="skip the per-element loop assembly baseline")
    ap.add_argument("--sheet", action="store_true", help="use square sheets even if the t-shirt exists")
    ap.add_argument("--checkpoint", action="store_true", help="recompute steps in backward (less memory)")
    ap.add_argument(
        "--dress",
        nargs="*",
        metavar="CASE",
        help="instead: dress each case folder's pattern_gt.json on its body (unsew drape's dress()) once "
        "per CHOLMOD mode of --modes, timed, and the drapes compared vertex by vertex",
    )
    ap.add_argument("--modes", default="supernodal,simplicial", help="CHOLMOD modes for --dress")
    return ap.parse_args(argv)


def _gap_mm(a, b) -> str:
    """Median and largest distance [mm] between two drapes (n, 3) [m] of one mesh ("n/a" where
    either diverged)."""
    if a is None or b is None:
        return f"{'n/a':>18}"
    d = np.linalg.norm(a - b, axis=1) * 1e3
    return f"{np.median(d):10.3f} {d.max():7.2f}"


def _dress_modes(cases: list[str], modes: list[str]) -> None:
    """One row per case: seconds of dress() in each CHOLMOD mode, its factorizations, and the
    median and largest distance [mm] between the first mode's drape and each other's."""
    import warnings

    import unsew.sim.solve as solve_mod
    from unsew.body.case import load_case
    from unsew.dress import dress
    from unsew.errors import SimulationError
    from unsew.io.garmentcode import load_pattern

    head = " | ".join(f"{m + ' s':>14} {'factor.':>7}" for m in modes)
    gaps = " | ".join(f"{m[:5]} vs {modes[0][:5]} mm: median max" for m in modes[1:])
    print(f"{'case':>12} {'verts':>6} | {head} | {gaps}")
    calls = []
    orig = solve_mod._Factor._factorize

    def counted(self, pattern, values):
        calls.append(1)
        return orig(self, pattern, values)

    solve_mod._Factor._factorize = counted
    try:
        for case in cases:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the reader's notes on the pattern (gathered seams...)
                body, pattern = load_case(Path(case)).body, load_pattern(Path(case) / "pattern_gt.json")
            cells, drapes = [], []
            for mode in modes:
                solve_mod.CHOLMOD_MODE = mode
                calls.clear()
                t0 = time.perf_counter()
                try:
                    drapes.append(dress(pattern, body).x.numpy())
                except SimulationError:
                    drapes.append(None)
                cells.append(f"{time.perf_counter() - t0:14.1f} {len(calls):7d}")
            n = len(drapes[0]) if drapes[0] is not None else 0
            gaps = " | ".join(_gap_mm(drapes[0], x) for x in drapes[1:])
            print(f"{Path(case).name:>12} {n:>6} | {' | '.join(cells)} | {gaps}", flush=True)
    finally:
        solve_mod._Factor._factorize = orig
        solve_mod.CHOLMOD_MODE = solve_mod.DEFAULT_CHOLMOD_MODE


def _variants(spec: str) -> list[tuple]:
    """(stencil, backend, fused, line_search) of each variant of ``spec`` whose backend is here."""
    from unsew.sim.solve import resolve_backend

    variants = []
    for v in spec.split(","):
        stencil, backend, *rest_ = v.split(":")
        try:
            resolve_backend(backend.partition("@")[0])
        except ImportError as exc:
            print(f"(skipping {v}: {exc})")
            continue
        variants.append((stencil, backend, "unfused" not in rest_, "nols" not in rest_))
    return variants


def _time_drapes(models, st, sdf, uvt, gamma, variants, args) -> dict:
    """variant -> {steps: (forward s, backward s) min over the repeats, "rss": MB}."""
    res = {v: {} for v in variants}
    for v in variants:  # warm-up (CHOLMOD's one analysis per topology is not timed)
        _run(models[v[0]], st, sdf, uvt, gamma, 1, checkpoint=args.checkpoint, variant=v)
    for steps in (1, 20):
        for _ in range(args.repeat):
            for v in variants:
                r0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                fw, rv = _run(models[v[0]], st, sdf, uvt, gamma, steps, checkpoint=args.checkpoint, variant=v)
                r1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                b = res[v].get(steps, (np.inf, np.inf))
                res[v][steps] = (min(b[0], fw), min(b[1], rv))
                if steps == 20:
                    res[v]["rss"] = max(res[v].get("rss", 0), (r1 - r0) / 1024)
    return res


def _time_solvers(models, rest, Hm, Hb, n) -> dict:
    """(stencil, backend) -> (seconds of a factorization and two solves, min of 3; nnz) on the
    step-0 system of each stencil."""
    from unsew.sim.assembly import scatter_blocks
    from unsew.sim.integrator import _ring_weight
    from unsew.sim.solve import SparsePattern, _Factor, resolve_backend

    tb = {}
    for stencil, m in sorted(models.items()):
        Hb_s = Hb * _ring_weight(Hb) if stencil == "ring" else Hb
        K = scatter_blocks(m.nnz, m.tri_src, m.tri_dst, Hm) + scatter_blocks(
            m.nnz, m.hinge_src, m.hinge_dst, Hb_s
        )
        A = 0.0025 * K
        A[m.diag_dst] += rest.mass.repeat_interleave(3)
        pat = SparsePattern(3 * n, m.rows, m.cols)
        b = np.random.default_rng(0).standard_normal(3 * n)
        for name in ("cholespy", "cholmod@simplicial", "cholmod@supernodal", "scipy"):
            be = _backend_mode(name)
            try:
                resolve_backend(be)
            except ImportError:
                continue
            _Factor(pat, A.numpy(), be)  # CHOLMOD: analysis once per pattern and mode, not timed
            t = np.inf
            for _ in range(3):
                t0 = time.perf_counter()
                fac = _Factor(pat, A.numpy(), be)
                fac.solve(b)
                fac.solve(b)
                t = min(t, time.perf_counter() - t0)
                del fac
            tb[(stencil, name)] = (t, m.nnz)
    _backend_mode("cholmod")
    return tb


def _backend_mode(name: str) -> str:
    """The backend of a name "backend[@mode]", CHOLMOD's factorization mode set from it (the
    library's default where none is named)."""
    import unsew.sim.solve as solve_mod

    be, _, mode = name.partition("@")
    solve_mod.CHOLMOD_MODE = mode or solve_mod.DEFAULT_CHOLMOD_MODE
    return be


def _time_assembly(models, st, uvt, gamma, n, no_loop: bool):
    """(loop assembly s (nan with no_loop), index-map assembly s, :func:`_time_solvers`) on the
    initial state's element Hessians."""
    from unsew.sim.assembly import scatter_blocks
    from unsew.sim.energies.bending import energy_bending
    from unsew.sim.energies.membrane import energy_membrane
    from unsew.sim.integrator import rest_data

    model = models.get("full", next(iter(models.values())))
    rest = rest_data(model, uvt, 0.15)
    with torch.no_grad():
        _, _, Hm = energy_membrane(st.x, model.faces, rest.area, rest.B, gamma)
        _, _, Hb = energy_bending(st.x, model.hinges, rest.coef, gamma)
        t_loop = np.nan
        if not no_loop:
            t0 = time.perf_counter()
            _loop_assembly(model, Hm, Hb)
            t_loop = time.perf_counter() - t0
        t_ours = np.inf
        for _ in range(5):
            t0 = time.perf_counter()
            scatter_blocks(model.nnz, model.tri_src, model.tri_dst, Hm) + scatter_blocks(
                model.nnz, model.hinge_src, model.hinge_dst, Hb
            )
            t_ours = min(t_ours, time.perf_counter() - t0)
        return t_loop, t_ours, _time_solvers(models, rest, Hm, Hb, n)


def _print_solver_rows(solver_rows) -> None:
    print()
    print(
        f"{'mesh':>6} {'verts':>6} | {'asm loop':>8} {'asm ours':>8} {'speedup':>7} | factor + 2 solves [ms] "
        "(nnz of the lower triangle)"
    )
    for kind, n, t_loop, t_ours, tb, load in solver_rows:
        cells = "  ".join(f"{st_}:{be} {t * 1e3:6.1f} ({nnz})" for (st_, be), (t, nnz) in tb.items())
        print(
            f"{kind:>6} {n:>6} | {t_loop:8.3f} {t_ours:8.4f} {t_loop / t_ours:6.0f}x | {cells}  load "
            f"{load:.1f}"
        )
    print("fwd/rev: drape forward and backward (loss = sum |x|^2 on the final state) wrt uv and Gamma;")
    print(
        "RSS+: growth of peak resident memory during the 20-step runs (0 when an earlier size peaked higher);"
    )
    print("asm: assembly of the membrane + bending system blocks (one step); f+s: factor + two solves.")


def main(argv=None):
    args = _parse(argv)
    torch.set_num_threads(args.threads)
    print(f"load average at start: {os.getloadavg()[0]:.2f} (2 shared cores)")
    if args.dress is not None:
        _dress_modes(args.dress, args.modes.split(","))
        return
    from unsew.sim import MATERIALS, SimModel, SimState, SphereSDF

    gamma = MATERIALS["cotton"].gamma()
    sdf = SphereSDF((0.0, 0.0, 0.0), 0.1)
    variants = _variants(args.variants)
    print(f"torch {torch.__version__}, {args.threads} torch thread(s), min of {args.repeat} runs, seconds")
    hdr = (
        f"{'mesh':>6} {'verts':>6} {'faces':>6} {'variant':>23} | {'fwd 1':>6} {'fwd 20':>7} {'rev 1':>6} "
        f"{'rev 20':>7} {'f+r 20':>7} | {'RSS+ MB':>7} | {'load':>4}"
    )
    print(hdr)
    print("-" * len(hdr))
    solver_rows = []
    for n_target in [int(s) for s in args.sizes.split(",")]:
        kind, f, fuv, uv, x, n = _mesh(n_target, not args.sheet)
        models = {
            st_: SimModel.build(f, fuv, n=n, bending_stencil=st_) for st_ in sorted({v[0] for v in variants})
        }
        uvt = torch.as_tensor(uv, dtype=torch.float64)
        st = SimState.at_rest(x)
        res = _time_drapes(models, st, sdf, uvt, gamma, variants, args)
        load = os.getloadavg()[0]
        for v in variants:
            r = res[v]
            name = v[0] + ":" + v[1] + ("" if v[2] else ":unfused") + ("" if v[3] else ":nols")
            print(
                f"{kind:>6} {n:>6} {f.shape[0]:>6} {name:>23} | {r[1][0]:6.3f} {r[20][0]:7.3f} "
                f"{r[1][1]:6.3f} {r[20][1]:7.3f} {r[20][0] + r[20][1]:7.3f} | {r['rss']:7.0f} | {load:4.1f}",
                flush=True,
            )
        t_loop, t_ours, tb = _time_assembly(models, st, uvt, gamma, n, args.no_loop)
        solver_rows.append((kind, n, t_loop, t_ours, tb, os.getloadavg()[0]))
    _print_solver_rows(solver_rows)


if __name__ == "__main__":
    main()
