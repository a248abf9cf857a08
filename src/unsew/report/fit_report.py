"""One call for the fit loop: every figure of a fit plus report.html, in a result folder.

``write_fit_report(out_dir, target=..., result=..., ...)`` writes ``out_dir/figures/*.png``
and ``out_dir/report.html`` (figures embedded, so the HTML stands alone). Missing inputs
just leave their figure out. Call it inside the fit's temporary result folder
(``unsew.io.atomic.atomic_dir``) so a failed run leaves no report that looks finished.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np

from unsew.report.figures import pattern_outlines, plot_histogram, plot_loss_curves, plot_patterns
from unsew.report.html import write_report
from unsew.report.measure import measurement_table
from unsew.report.render import HEAT_CMAP, Colors, Layout, render_comparison, render_views

__all__ = ["write_fit_report", "FitReport", "nearest_distance_mm"]


def nearest_distance_mm(verts: np.ndarray, target_verts: np.ndarray) -> np.ndarray:
    """Distance [mm], shape (V,), float64, from each of ``verts`` (V, 3) [m] to the nearest of
    ``target_verts`` (T, 3) [m] (vertex to vertex: an upper bound of the distance to the
    target surface, close to it on meshes of similar resolution)."""
    from scipy.spatial import cKDTree

    d, _ = cKDTree(np.asarray(target_verts, dtype=np.float64)).query(np.asarray(verts, dtype=np.float64))
    return d * 1000.0


def _outlines(p) -> list:
    """A Pattern, or an already made list of (name, outline[, placement]) tuples."""
    if hasattr(p, "panels") and hasattr(p, "panel_order"):
        return pattern_outlines(p)
    return list(p)


@dataclass(frozen=True)
class FitReport:
    """What :func:`write_fit_report` draws and tabulates; every field may be left out.

    Attributes:
        title: the page's title.
        summary, metrics, config, notes, choices: as :func:`unsew.report.html.write_report`.
            The metrics tables are preceded by the panel measurements of ``patterns``
            (:func:`unsew.report.measure.measurement_table`, cm) and the result's ``material``;
            a per-iteration ``loss_history`` entry is left out of the tables when ``history``
            is plotted.
        target, result, body: (verts (V, 3) [m], faces (F, 3) int) in the world frame.
        distance_mm: per-vertex distance of the result to the target [mm], shape (V_result,);
            default: to the nearest target vertex (:func:`nearest_distance_mm`).
        history, phases: as :func:`unsew.report.figures.plot_loss_curves`.
        patterns: (label, Pattern or list of (name, outline (M, 2) [m])) in drawing order, e.g.
            ``[("base", base), ("graded", graded), ("final", final), ("ground truth", gt)]``.
        views: the views of the mesh figures (:data:`unsew.report.render.VIEWS`).
        material: the result's material (SI values, as ``unsew.sim.material.material_to_dict``
            gives them).
    """

    title: str = "unsew fit"
    summary: Mapping[str, Any] | None = None
    metrics: Mapping[str, Any] | None = None
    target: tuple[np.ndarray, np.ndarray] | None = None
    result: tuple[np.ndarray, np.ndarray] | None = None
    body: tuple[np.ndarray, np.ndarray] | None = None
    distance_mm: np.ndarray | None = None
    history: Mapping[str, Sequence[float]] | None = None
    phases: Sequence[tuple[int, str]] | None = None
    patterns: Sequence[tuple[str, Any]] | None = None
    config: Mapping[str, Any] | None = None
    notes: Sequence[str] | None = None
    views: Sequence[str] = ("front", "side")
    material: Mapping[str, Any] | None = None
    choices: Sequence[str] | None = None


def write_fit_report(out_dir: str | os.PathLike, **fields) -> Path:
    """Draw the figures of a fit into ``out_dir/figures`` and write ``out_dir/report.html``.

    fields: the fields of :class:`FitReport` by name (all optional; an unknown name is a
    TypeError). Missing inputs leave their figure or table out. Returns the path of report.html.
    """
    r = FitReport(**fields)
    out = Path(out_dir)
    fig_dir = out / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    notes = list(r.notes or [])
    figures = _fit_figures(fig_dir, r, notes)
    tables = _fit_tables(patterns=r.patterns, material=r.material, metrics=r.metrics, history=r.history)
    return write_report(
        out / "report.html",
        title=r.title,
        summary=dict(r.summary or {}),
        metrics=tables,
        figures=figures,
        config=r.config,
        notes=notes or None,
        choices=r.choices,
    )


def _fit_figures(fig_dir: Path, r: FitReport, notes: list) -> list[tuple[str, Path]]:
    """Draw the figures :func:`write_fit_report` has inputs for into ``fig_dir``; returns
    their (caption, PNG path) in report order. A note is appended to ``notes`` when the
    distances are computed here."""
    figures: list[tuple[str, Path]] = []
    history, phases, target, result, views = r.history, r.phases, r.target, r.result, r.views
    if history:
        figures.append(
            (
                "Loss per iteration: the total and each term"
                + (", with the phases of the fit" if phases else ""),
                plot_loss_curves(fig_dir / "loss.png", history, phases=phases),
            )
        )
    if target is not None and result is not None:
        figures += _distance_figures(
            fig_dir, target, result, body=r.body, distance_mm=r.distance_mm, views=views, notes=notes
        )
    elif result is not None:
        figures.append(
            (
                "Fitted result",
                render_views(
                    fig_dir / "result.png",
                    result[0],
                    result[1],
                    body=r.body,
                    layout=Layout(views=tuple(views)),
                ),
            )
        )
    if r.patterns:
        pats = [(str(label), _outlines(p)) for label, p in r.patterns]
        figures.append(
            (
                ", ".join(label for label, _ in pats) + " patterns, panel by panel, at true scale",
                plot_patterns(fig_dir / "patterns.png", pats),
            )
        )
    return figures


def _distance_figures(
    fig_dir: Path, target, result, *, body, distance_mm, views, notes: list
) -> list[tuple[str, Path]]:
    """Target against result, the result coloured by its distance to the target [mm] (the
    nearest target vertex when ``distance_mm`` is None, noted in ``notes``) and the distances'
    histogram (when any is finite): (caption, PNG path) each."""
    figures = [
        (
            "Target (top) and fitted result (bottom), same views and scale",
            render_comparison(
                fig_dir / "target_vs_result.png",
                target,
                result,
                body=body,
                layout=Layout(views=tuple(views), frame="all"),
            ),
        )
    ]
    if distance_mm is None:
        distance_mm = nearest_distance_mm(result[0], target[0])
        notes.append("Heat map distances are to the nearest target vertex.")
    d = np.asarray(distance_mm, dtype=np.float64)
    finite = d[np.isfinite(d)]
    vmax = float(np.percentile(finite, 98)) if finite.size else 1.0
    figures.append(
        (
            f"Distance of the result to the target [mm] (colour scale capped at the "
            f"98th percentile, {vmax:.2g} mm)",
            render_views(
                fig_dir / "distance.png",
                result[0],
                result[1],
                vertex_values=d,
                body=body,
                colors=Colors(
                    cmap=HEAT_CMAP,
                    vmin=0.0,
                    vmax=vmax if vmax > 0 else 1.0,
                    colorbar_label="distance to target [mm]",
                ),
                layout=Layout(views=tuple(views) + (("back",) if "back" not in views else ()), frame="all"),
            ),
        )
    )
    if finite.size:
        figures.append(
            (
                "Histogram of the per-vertex distance to the target",
                plot_histogram(fig_dir / "distance_hist.png", d),
            )
        )
    return figures


def _fit_tables(*, patterns, material, metrics, history) -> dict[str, Any]:
    """The report's metric tables: panel measurements of ``patterns`` [cm], the result's
    ``material``, then ``metrics`` (without ``loss_history`` when ``history`` is plotted)."""
    tables: dict[str, Any] = {}
    if patterns:
        rows = measurement_table(list(patterns))
        if rows:
            tables["panel measurements"] = {
                r["measurement"]: {k: v for k, v in r.items() if k != "measurement"} for r in rows
            }
    if material:
        tables["material of the result"] = dict(material)
    for k, v in (metrics or {}).items():
        if history and k == "loss_history":
            continue  # plotted above; every value stays in metrics.json
        tables[k] = v
    return tables
