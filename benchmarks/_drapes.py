"""Shared table cells of the drape benchmarks (bench_gcdrape.py, bench_gcbodies.py)."""

from __future__ import annotations


def verdict_cells(v, d) -> dict:
    """A dressed garment's row cells from its :func:`unsew.sim.checks.check_dressed` verdict ``v``:
    verdict ("ok" or the reason), share of vertices inside the body [%], height range [m], largest
    and 99th-percentile edge stretch [-], share of vertices far off the body [%], and the vertex
    count of ``d`` (a :class:`unsew.dress.Dressed`)."""
    return dict(
        verdict="ok" if v.ok else v.reason,
        inside_pct=v.inside_pct,
        y_range=f"{v.y_min:.2f}..{v.y_max:.2f}",
        stretch_max=v.stretch_max,
        stretch_p99=v.stretch_p99,
        off_body_pct=v.far_pct,
        verts=int(d.mesh.n_x),
    )
