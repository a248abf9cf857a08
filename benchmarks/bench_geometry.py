"""Which BVH library for point-to-mesh distance, closest points and inside tests: time and peak memory
of libigl, fcpw, embreex and the old KD-tree-of-centroids search.

    PYTHONPATH=src python -m benchmarks geometry [--quick] [--mem-limit-gb 4]

Closest points: garment-like tubes (benchmarks/_meshes.py) of 5K/20K/50K triangles, 5K/20K/50K
query points within 1 cm of the surface; then the hard cases: a tube whose hem band has triangles
100x the median area ("uneven") and queries 30 cm away from the surface ("30 cm"). Inside tests:
the default body (closed, 26.7K triangles), queries uniform in its bounding box, checked against
libigl's exact winding number. embreex (Embree rays, trimesh's backend) has no closest-point
query, so it appears in the inside table only.

Each measurement runs in a fresh process; "peak MB" is the growth of the process's peak resident
set (VmHWM, reset just before the build) over its size at that moment, so it counts C++ memory
too. The old search runs under an address-space limit (--mem-limit-gb) and a time limit; rows it
could not finish say so. "err um" is the largest distance difference from libigl [micrometres].
Prints tables; never asserts timings.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _rss_kb(field: str) -> int:
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def _reset_peak() -> int:
    """Reset VmHWM to the current RSS; return the current RSS [kB]."""
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
    except OSError:
        pass
    return _rss_kb("VmRSS")


# -- one measurement, in a worker process -----------------------------------------------------


def _closest(lib, V, F, Q):
    """Returns (build seconds, query seconds, distances (P,) [m])."""
    import numpy as np

    if lib == "igl":
        import igl

        t = time.perf_counter()
        tree = igl.AABB()
        tree.init(V, F)
        t1 = time.perf_counter()
        sq, _, _ = tree.squared_distance(V, F, Q)
        return t1 - t, time.perf_counter() - t1, np.sqrt(sq)
    if lib == "igl, Morton order":  # unsew.geometry.distance.MeshQuery: queries sorted along a Z-curve
        from unsew.geometry.distance import MeshQuery

        t = time.perf_counter()
        mq = MeshQuery(V, F)
        t1 = time.perf_counter()
        d = mq.distance(Q)
        return t1 - t, time.perf_counter() - t1, d
    if lib == "fcpw":
        import fcpw

        t = time.perf_counter()
        scene = _fcpw_scene(V, F)
        t1 = time.perf_counter()
        hits = fcpw.interaction_3D_list()
        scene.find_closest_points(
            np.asfortranarray(Q, dtype=np.float32), np.full(len(Q), np.inf, np.float32), hits
        )
        d = np.array([h.d for h in hits], dtype=np.float64)  # results come back as Python objects
        return t1 - t, time.perf_counter() - t1, d
    if lib == "kdtree (old)":
        from _kdtree_closest import closest_points_kdtree

        t = time.perf_counter()
        _, d, _ = closest_points_kdtree(Q, V, F)
        return 0.0, time.perf_counter() - t, d
    raise ValueError(lib)


def _fcpw_scene(V, F):
    """An fcpw BVH scene of one triangle mesh (float32, as fcpw stores it)."""
    import fcpw
    import numpy as np

    scene = fcpw.scene_3D()
    scene.set_object_count(1)
    scene.set_object_vertices(np.asfortranarray(V, dtype=np.float32), 0)
    scene.set_object_triangles(np.asfortranarray(F, dtype=np.int32), 0)
    scene.build(fcpw.aggregate_type.bvh_surface_area, True)
    return scene


def _inside(lib, V, F, Q):
    """Returns (build seconds, query seconds, inside (P,) bool)."""
    import numpy as np

    if lib == "igl fast winding number":
        import igl

        t = time.perf_counter()
        w = igl.fast_winding_number(V, F, Q)
        return 0.0, time.perf_counter() - t, w > 0.5
    if lib == "igl winding number (exact)":
        import igl

        t = time.perf_counter()
        w = igl.winding_number(V, F, Q)
        return 0.0, time.perf_counter() - t, w > 0.5
    if lib == "fcpw contains":
        t = time.perf_counter()
        scene = _fcpw_scene(V, F)
        t1 = time.perf_counter()
        out = np.zeros(len(Q), np.int32)
        scene.contains(np.asfortranarray(Q, dtype=np.float32), out)
        return t1 - t, time.perf_counter() - t1, out > 0
    if lib == "embreex rays (trimesh)":
        import trimesh
        from trimesh.ray.ray_pyembree import RayMeshIntersector

        t = time.perf_counter()
        ray = RayMeshIntersector(trimesh.Trimesh(V, F, process=False))
        t1 = time.perf_counter()
        inside = ray.contains_points(Q)
        return t1 - t, time.perf_counter() - t1, np.asarray(inside, bool)
    raise ValueError(lib)


def _worker(spec: dict) -> dict:
    import resource

    import numpy as np

    import _meshes

    if spec.get("mem_limit_gb"):
        lim = int(spec["mem_limit_gb"] * 2**30)
        resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
    if spec["kind"] == "closest":
        V, F = _meshes.tube(spec["faces"], uneven=spec["uneven"])
        Q = _meshes.queries(V, F, spec["queries"], away=spec["away"])
        fn = _closest
    else:
        from unsew.body.body import default_body

        body = default_body()
        V, F = body.verts, body.faces.astype(np.int64)
        rng = np.random.default_rng(0)
        lo, hi = V.min(0) - 0.05, V.max(0) + 0.05
        Q = lo + (hi - lo) * rng.random((spec["queries"], 3))
        fn = _inside
    # import the library before the baseline, so the peak counts the build and queries only
    mod = {"igl": "igl", "fcpw": "fcpw", "embreex": "embreex"}.get(spec["lib"].replace(",", " ").split()[0])
    try:
        if mod:
            __import__(mod)
        if "Morton" in spec["lib"]:
            import unsew.geometry.distance  # noqa: F401
    except ImportError:
        return {"status": f"{mod} not installed (pip install -e .[bench])"}
    base = _reset_peak()
    try:
        t_build, t_query, out = fn(spec["lib"], V, F, Q)
    except MemoryError:
        return {"status": f"MemoryError (limit {spec['mem_limit_gb']:g} GB)"}
    peak_mb = (_rss_kb("VmHWM") - base) / 1024.0
    res = {"status": "ok", "build_s": t_build, "query_s": t_query, "peak_MB": peak_mb, "faces": len(F)}
    import igl

    if spec["kind"] == "closest":
        sq, _, _ = igl.point_mesh_squared_distance(Q, V, F)
        res["err_um"] = float(np.abs(out - np.sqrt(sq)).max() * 1e6)
    else:
        ref = igl.winding_number(V, F, Q) > 0.5
        res["disagree"] = int((out != ref).sum())
    return res


def _run(spec: dict, timeout: float) -> dict:
    env = dict(os.environ)
    here = os.path.dirname(os.path.abspath(__file__))
    env["PYTHONPATH"] = os.pathsep.join([here, env.get("PYTHONPATH", "")])
    try:
        r = subprocess.run(
            [sys.executable, os.path.abspath(__file__), "--worker", json.dumps(spec)],
            capture_output=True,
            text=True,
            timeout=timeout,
            env=env,
        )
    except subprocess.TimeoutExpired:
        return {"status": f"not done in {timeout:g} s"}
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["?"])[-1]
        limit = f" under the {spec['mem_limit_gb']:g} GB limit" if spec.get("mem_limit_gb") else ""
        return {"status": f"failed{limit}: {last[:60]}"}
    return json.loads(r.stdout.strip().splitlines()[-1])


def _closest_rows(sizes, args) -> list[dict]:
    """One row per closest-point case and library (each measured in a worker process)."""
    libs = args.libs
    rows = []
    cases = [(f, q, False, 0.0) for f in sizes for q in sizes]
    big = sizes[-1]
    cases += [(big, big, True, 0.0), (big, big, False, 0.3), (big, big, True, 0.3)]
    for faces, nq, uneven, away in cases:
        for lib in libs:
            spec = {
                "kind": "closest",
                "lib": lib,
                "faces": faces,
                "queries": nq,
                "uneven": uneven,
                "away": away,
                "mem_limit_gb": args.mem_limit_gb if lib.startswith("kdtree") else None,
            }
            r = _run(spec, args.timeout)
            mesh = ("uneven " if uneven else "") + "tube"
            rows.append(
                {
                    "library": lib,
                    "mesh": mesh,
                    "triangles": r.get("faces", faces),
                    "queries": nq,
                    "away": f"{away * 100:g} cm",
                    "build s": r.get("build_s"),
                    "query s": r.get("query_s"),
                    "peak MB": r.get("peak_MB"),
                    "err um": r.get("err_um"),
                    "status": r["status"],
                }
            )
            print(rows[-1], file=sys.stderr, flush=True)
    return rows


def _inside_rows(sizes, timeout: float) -> list[dict]:
    """One row per inside-test library and query count (each measured in a worker process)."""
    rows = []
    for nq in sizes:
        for lib in [
            "igl fast winding number",
            "igl winding number (exact)",
            "fcpw contains",
            "embreex rays (trimesh)",
        ]:
            r = _run({"kind": "inside", "lib": lib, "queries": nq}, timeout)
            rows.append(
                {
                    "library": lib,
                    "triangles": r.get("faces"),
                    "queries": nq,
                    "build s": r.get("build_s"),
                    "query s": r.get("query_s"),
                    "peak MB": r.get("peak_MB"),
                    "wrong vs exact winding": r.get("disagree"),
                    "status": r["status"],
                }
            )
            print(rows[-1], file=sys.stderr, flush=True)
    return rows


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--worker", help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true", help="5K-triangle meshes and 5K queries only")
    ap.add_argument("--mem-limit-gb", type=float, default=4.0, help="address-space limit of the old search")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per measurement")
    ap.add_argument(
        "--libs",
        nargs="+",
        default=["igl", "igl, Morton order", "fcpw", "kdtree (old)"],
        help="closest-point libraries to measure",
    )
    ap.add_argument("--no-inside", action="store_true", help="skip the inside-test table")
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(_worker(json.loads(args.worker))))
        return
    from tables import print_table

    sizes = [5000] if args.quick else [5000, 20000, 50000]
    print_table(
        _closest_rows(sizes, args),
        title="Closest points on a triangle mesh (time [s], peak memory growth [MB], error against libigl "
        "[um])",
        digits=3,
    )
    if args.no_inside:
        return
    print_table(
        _inside_rows(sizes, args.timeout),
        title="Inside tests on the default body (closed, queries uniform in its bounding box)",
        digits=3,
    )


if __name__ == "__main__":
    main()
