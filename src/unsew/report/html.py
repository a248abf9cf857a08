"""The HTML report of a fit: one self-contained file (figures embedded as base64 data URIs, so
it survives being moved or mailed), written atomically so a failure leaves no report behind.

Metric names carry their unit. A key's unit suffix is shown in brackets: ``chamfer_mm`` is
shown as ``chamfer [mm]`` (the raw key stays in the cell's tooltip), keys already holding
``[...]`` are shown as they are. The rows of a table whose own key carries a unit (``timings_s``,
``peak_memory_stages_mb``) are in that unit: their keys are shown without a unit suffix of their
own (a stage named ``body_sdf_s`` in the memory table is "body sdf", not "body sdf [s]"). There
is no minutes suffix: ``y_min`` is "y min".
"""

from __future__ import annotations

import base64
import datetime as _dt
import html as _html
import math
import os
from pathlib import Path
from typing import Any, Mapping, Sequence

from unsew import __version__
from unsew.errors import InputError
from unsew.io.atomic import atomic_write

__all__ = ["write_report", "pretty_key"]

# key suffix -> unit shown in brackets (longest suffixes first when matching)
_UNITS = {
    "kg_per_m2": "kg/m²",
    "m_s": "m/s",
    "n_per_m": "N/m",
    "n_m": "N·m",
    "percent": "%",
    "pct": "%",
    "deg": "deg",
    "rad": "rad",
    "mm": "mm",
    "cm": "cm",
    "m2": "m²",
    "m": "m",
    "ms": "ms",
    "s": "s",
    "mb": "MB",
    "kg": "kg",
    "px": "px",
}

_MIME = [
    (b"\x89PNG\r\n\x1a\n", "image/png"),
    (b"\xff\xd8\xff", "image/jpeg"),
    (b"GIF8", "image/gif"),
]


def pretty_key(key: str) -> str:
    """A metric key as shown in a table: underscores to spaces, a unit suffix in brackets.

    ``"chamfer_mm"`` -> ``"chamfer [mm]"``, ``"area_error_pct"`` -> ``"area error [%]"``,
    ``"time [s]"`` -> ``"time [s]"``.
    """
    k = str(key)
    if "[" in k:
        return k
    low = k.lower()
    for suffix in sorted(_UNITS, key=len, reverse=True):
        tail = "_" + suffix
        if low.endswith(tail) and len(k) > len(tail):
            return f"{k[: -len(tail)].replace('_', ' ')} [{_UNITS[suffix]}]"
    return k.replace("_", " ")


def _unit(key: str) -> str | None:
    """The unit a key's suffix names (``chamfer_mm`` -> ``mm``), or None."""
    k = str(key)
    if "[" in k:
        return k[k.index("[") + 1 : k.rindex("]")] if "]" in k else None
    low = k.lower()
    for suffix in sorted(_UNITS, key=len, reverse=True):
        if low.endswith("_" + suffix) and len(k) > len(suffix) + 1:
            return _UNITS[suffix]
    return None


def _bare_key(key: str) -> str:
    """A key as shown in a table whose heading gives the unit: no unit suffix of its own."""
    k = str(key)
    if "[" in k:
        return k[: k.index("[")].strip()
    shown = pretty_key(k)
    return shown[: shown.index(" [")] if shown.endswith("]") and " [" in shown else shown


def _fmt(v: Any) -> str:
    """A value as table text: floats with 4 significant digits, ints with thin-space groups."""
    try:
        import numpy as np

        if isinstance(v, np.generic):
            v = v.item()
        elif isinstance(v, np.ndarray):
            v = v.tolist()
    except ImportError:  # pragma: no cover
        pass
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, int):
        return f"{v:,}".replace(",", "\u2009")
    if isinstance(v, float):
        if math.isnan(v):
            return "n/a"
        if math.isinf(v):
            return "∞" if v > 0 else "−∞"
        return f"{v:.4g}"
    if isinstance(v, (list, tuple)):
        nums = [x for x in v if isinstance(x, (int, float)) and not isinstance(x, bool)]
        if len(v) > _MAX_LISTED and len(nums) == len(v):  # a series: its shape, not a wall of numbers
            return (
                f"{len(v)} values, {_fmt(v[0])} → {_fmt(v[-1])} "
                f"(min {_fmt(min(nums))}, max {_fmt(max(nums))})"
            )
        return ", ".join(_fmt(x) for x in v)
    return str(v)


#: Longest list of numbers a table cell shows in full; longer ones are summarised.
_MAX_LISTED = 6


def _esc(s: Any) -> str:
    return _html.escape(str(s), quote=True)


def _is_scalar(v: Any) -> bool:
    if isinstance(v, Mapping):
        return False
    if isinstance(v, (list, tuple)):
        return all(not isinstance(x, (Mapping, list, tuple)) for x in v)
    return True


def _num_class(v: Any) -> str:
    return ' class="num"' if isinstance(v, (int, float)) and not isinstance(v, bool) else ""


def _kv_table(
    items: Sequence[tuple[str, Any]], *, head=("quantity", "value"), unit: str | None = None
) -> str:
    show = _bare_key if unit else pretty_key
    rows = "".join(
        f'<tr><th scope="row" title="{_esc(k)}">{_esc(show(k))}</th>'
        f"<td{_num_class(_py(v))}>{_esc(_fmt(v))}</td></tr>"
        for k, v in items
    )
    head1 = f"{head[1]} [{unit}]" if unit else head[1]
    return (
        f'<table class="kv"><thead><tr><th>{_esc(head[0])}</th><th>{_esc(head1)}</th></tr>'
        f"</thead><tbody>{rows}</tbody></table>"
    )


def _records_table(rows: Sequence[tuple[str, Mapping]], *, first: str) -> str:
    cols: list[str] = []
    for _, r in rows:
        cols += [c for c in r if c not in cols]
    head = f"<th>{_esc(first)}</th>" + "".join(
        f'<th title="{_esc(c)}">{_esc(pretty_key(c))}</th>' for c in cols
    )
    body = "".join(
        f'<tr><th scope="row" title="{_esc(name)}">{_esc(pretty_key(name) if _unit(name) else name)}</th>'
        + "".join(f"<td{_num_class(_py(r.get(c)))}>{_esc(_fmt(r.get(c)))}</td>" for c in cols)
        + "</tr>"
        for name, r in rows
    )
    return f'<table class="grid"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def _py(v):
    try:
        import numpy as np

        if isinstance(v, np.generic):
            return v.item()
    except ImportError:  # pragma: no cover
        pass
    return v


def _metrics_html(metrics: Mapping, depth: int = 0, unit: str | None = None) -> str:
    """Nested metrics as tables: scalars of one level in a two-column table, a dict of flat dicts
    (or a list of flat dicts) as one table with a row per entry, deeper levels as subsections.
    ``unit``: the unit the enclosing key names, which its entries are in."""
    out = []
    scalars = [(k, v) for k, v in metrics.items() if _is_scalar(v)]
    if scalars:
        out.append(_kv_table(scalars, unit=unit))
    hn = min(3 + depth, 6)
    for k, v in metrics.items():
        if _is_scalar(v):
            continue
        title = f"<h{hn}>{_esc(_bare_key(k) if unit else pretty_key(k))}</h{hn}>"
        if (
            isinstance(v, Mapping)
            and v
            and all(isinstance(r, Mapping) and all(_is_scalar(x) for x in r.values()) for r in v.values())
        ):
            out.append(title + _records_table([(str(n), r) for n, r in v.items()], first="name"))
        elif (
            isinstance(v, (list, tuple))
            and v
            and all(isinstance(r, Mapping) and all(_is_scalar(x) for x in r.values()) for r in v)
        ):
            out.append(title + _records_table([(str(i), r) for i, r in enumerate(v)], first="#"))
        elif isinstance(v, Mapping):
            out.append(
                f'<section class="sub">{title}{_metrics_html(v, depth + 1, _unit(k) or unit)}</section>'
            )
        else:  # a list holding lists or mixed things
            out.append(title + f"<pre>{_esc(v)}</pre>")
    return "".join(out)


def _plain(x: Any) -> Any:
    """Config values as plain YAML-able Python (numpy, tuples, paths, dataclasses)."""
    import dataclasses

    try:
        import numpy as np

        if isinstance(x, np.generic):
            return x.item()
        if isinstance(x, np.ndarray):
            return x.tolist()
    except ImportError:  # pragma: no cover
        pass
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return {f.name: _plain(getattr(x, f.name)) for f in dataclasses.fields(x)}
    if isinstance(x, Mapping):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, set)):
        return [_plain(v) for v in x]
    if isinstance(x, os.PathLike):
        return os.fspath(x)
    if isinstance(x, (str, int, float, bool)) or x is None:
        return x
    return str(x)


def _config_text(config: Mapping) -> str:
    try:
        import yaml

        return yaml.safe_dump(_plain(config), sort_keys=False, default_flow_style=False, allow_unicode=True)
    except ImportError:  # pragma: no cover
        import json

        return json.dumps(_plain(config), indent=2)


def _load_figure(caption: str, path, base: Path) -> str:
    """The figure as a data URI; InputError if it is missing or not an image."""
    p = Path(path)
    if not p.is_absolute() and not p.exists() and (base / p).exists():
        p = base / p
    if not p.is_file():
        raise InputError(f"figure {caption!r}: image file {os.fspath(path)} not found; nothing was written")
    data = p.read_bytes()
    mime = next((m for sig, m in _MIME if data.startswith(sig)), None)
    if mime is None and p.suffix.lower() == ".svg" and b"<svg" in data[:4096]:
        mime = "image/svg+xml"
    if mime is None:
        raise InputError(f"figure {caption!r}: {p} is not a PNG, JPEG, GIF or SVG image; nothing was written")
    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"


_CSS = """
:root { --ink:#1f2328; --muted:#656d76; --line:#d8dee4; --soft:#f6f8fa; --accent:#2f6fd0; }
* { box-sizing: border-box; }
body { margin:0; color:var(--ink); background:#fff; line-height:1.5;
       font:15px/1.5 -apple-system, "Segoe UI", Helvetica, Arial, sans-serif; }
main { max-width:1180px; margin:0 auto; padding:28px 28px 60px; }
header h1 { margin:0 0 4px; font-size:26px; }
header p { margin:0; color:var(--muted); font-size:13px; }
nav { margin:14px 0 8px; font-size:13px; }
nav a { color:var(--accent); text-decoration:none; margin-right:14px; }
h2 { font-size:19px; margin:36px 0 12px; padding-bottom:6px; border-bottom:1px solid var(--line); }
h3 { font-size:16px; margin:22px 0 8px; }
h4, h5, h6 { font-size:14px; margin:16px 0 6px; color:var(--muted); }
.cards { display:grid; grid-template-columns:repeat(auto-fill, minmax(190px, 1fr)); gap:10px; }
.card { border:1px solid var(--line); border-radius:8px; padding:10px 14px; background:var(--soft); }
.card .k { font-size:12px; color:var(--muted); }
.card .v { font-size:19px; font-weight:600; font-variant-numeric:tabular-nums; word-break:break-word; }
table { border-collapse:collapse; margin:6px 0 14px; font-size:14px; }
th, td { padding:5px 12px; border-bottom:1px solid var(--line); text-align:left; vertical-align:top; }
thead th { background:var(--soft); font-weight:600; border-bottom:2px solid var(--line); }
tbody th { font-weight:500; }
tbody tr:nth-child(even) { background:#fbfbfc; }
td.num { text-align:right; font-variant-numeric:tabular-nums; white-space:nowrap; }
table.kv { min-width:420px; }
.sub { margin-left:10px; }
figure { margin:0 0 24px; border:1px solid var(--line); border-radius:8px; padding:12px; }
figure img { display:block; max-width:100%; height:auto; margin:0 auto; }
figcaption { margin-top:8px; font-size:14px; color:var(--muted); text-align:center; }
ul.notes li { margin:4px 0; }
details summary { cursor:pointer; color:var(--accent); }
pre { background:var(--soft); border:1px solid var(--line); border-radius:6px; padding:12px;
      overflow:auto; font-size:13px; line-height:1.4; }
footer { margin-top:40px; font-size:12px; color:var(--muted); }
@media print { nav { display:none; } figure { break-inside:avoid; } }
"""


def write_report(
    path_html: str | os.PathLike,
    *,
    title: str,
    summary: Mapping[str, Any],
    metrics: Mapping[str, Any],
    figures: Sequence[tuple[str, str | os.PathLike]],
    config: Mapping[str, Any] | None = None,
    notes: Sequence[str] | None = None,
    choices: Sequence[str] | None = None,
) -> Path:
    """Write the report of a fit as one self-contained HTML file; returns its path.

    title: the page's heading. summary: key facts (name -> value) shown first as cards, e.g.
    ``{"garment": "tshirt", "chamfer_mm": 1.8, "iterations": 200, "time_s": 312.0}``.
    metrics: name -> value, nested dicts allowed: each level a table; a dict of flat dicts (e.g.
    per panel) becomes one table with a row per entry. Put the unit in the key (``_mm``,
    ``_pct``, ``_deg``, ``_s`` suffixes or ``"name [unit]"``). figures: (caption, image path)
    in order; PNG (or JPEG, GIF, SVG) files, embedded as base64 data URIs; a relative path that
    does not exist from the working folder is looked up beside ``path_html``. config: shown as
    YAML in a folded block. notes: short lines (warnings, remarks) listed under the summary.
    choices: sentences saying what was chosen and why (base, fabric, phase two kept or not),
    shown as "What was chosen and why" right after the summary cards.

    Every figure is read and checked before anything is written; a missing or non-image figure
    raises :class:`unsew.errors.InputError` naming it. The file is written to a temporary name
    in the same folder and renamed when complete, so a failure leaves no partial report.
    """
    path = Path(path_html)
    if not isinstance(summary, Mapping) or not isinstance(metrics, Mapping):
        raise InputError("write_report: summary and metrics must be dicts")
    embedded = _embed_figures(figures, path.parent)
    parts = _head(title)
    parts.append(_nav(notes=bool(notes), figures=bool(embedded), config=config is not None))
    parts += _summary_section(summary, notes, choices)
    parts += _figures_section(embedded)
    parts.append('<section id="metrics"><h2>Metrics</h2>')
    parts.append(_metrics_html(metrics) if metrics else "<p>No metrics were recorded.</p>")
    parts.append("</section>")
    if config is not None:
        parts.append(
            '<section id="config"><h2>Configuration</h2><details>'
            "<summary>everything needed to rerun (as in config.yaml)</summary>"
            f"<pre>{_esc(_config_text(config))}</pre></details></section>"
        )
    parts.append(_footer())
    text = "\n".join(parts)

    with atomic_write(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
        _chmod_like_new_file(tmp)
    return path


def _embed_figures(figures: Sequence[tuple[str, str | os.PathLike]], base: Path) -> list[tuple[str, str]]:
    """(caption, data URI) of each (caption, image path) figure, every file read and checked
    (:func:`_load_figure`; relative paths also looked up in ``base``)."""
    embedded = []
    for item in figures:
        try:
            caption, fpath = item
        except (TypeError, ValueError):
            raise InputError("write_report: each figure must be a (caption, path) pair") from None
        embedded.append((str(caption), _load_figure(str(caption), fpath, base)))
    return embedded


def _head(title: str) -> list[str]:
    """The page's opening lines up to its header: doctype, metadata, style, the heading with
    the unsew version and the time written."""
    return [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f'<meta name="generator" content="unsew {_esc(__version__)}">',
        f"<title>{_esc(title)}</title><style>{_CSS}</style></head><body><main>",
        f"<header><h1>{_esc(title)}</h1>",
        f"<p>unsew {_esc(__version__)} · written {_esc(_dt.datetime.now().strftime('%Y-%m-%d %H:%M'))}"
        "</p></header>",
    ]


def _nav(*, notes: bool, figures: bool, config: bool) -> str:
    """The links to the page's sections, those present only."""
    nav = [("summary", "Summary")]
    if notes:
        nav.append(("notes", "Notes"))
    if figures:
        nav.append(("figures", "Figures"))
    nav.append(("metrics", "Metrics"))
    if config:
        nav.append(("config", "Configuration"))
    return "<nav>" + "".join(f'<a href="#{a}">{_esc(t)}</a>' for a, t in nav) + "</nav>"


def _summary_section(
    summary: Mapping[str, Any], notes: Sequence[str] | None, choices: Sequence[str] | None = None
) -> list[str]:
    """The summary cards, what was chosen and why (when given), then the notes (when any)."""
    parts = ['<section id="summary"><h2>Summary</h2><div class="cards">']
    for k, v in summary.items():
        parts.append(
            f'<div class="card"><div class="k" title="{_esc(k)}">{_esc(pretty_key(k))}</div>'
            f'<div class="v">{_esc(_fmt(v))}</div></div>'
        )
    parts.append("</div></section>")
    if choices:
        parts.append('<section id="choices"><h2>What was chosen and why</h2><ul class="notes">')
        parts += [f"<li>{_esc(c)}</li>" for c in choices]
        parts.append("</ul></section>")
    if notes:
        parts.append('<section id="notes"><h2>Notes</h2><ul class="notes">')
        parts += [f"<li>{_esc(n)}</li>" for n in notes]
        parts.append("</ul></section>")
    return parts


def _figures_section(embedded: Sequence[tuple[str, str]]) -> list[str]:
    """The numbered figures (caption, data URI), none when there are none."""
    if not embedded:
        return []
    parts = ['<section id="figures"><h2>Figures</h2>']
    for i, (caption, uri) in enumerate(embedded, 1):
        parts.append(
            f'<figure id="fig{i}"><img src="{uri}" alt="{_esc(caption)}">'
            f"<figcaption>Figure {i}. {_esc(caption)}</figcaption></figure>"
        )
    parts.append("</section>")
    return parts


def _footer() -> str:
    """The page's closing line."""
    return (
        f"<footer>Made by unsew {_esc(__version__)}. Units are given in the names of the "
        "quantities; renders are orthographic.</footer></main></body></html>\n"
    )


def _chmod_like_new_file(p: Path) -> None:
    """Give the temporary file (created private, 0600) the mode a plain new file would get."""
    mask = os.umask(0)
    os.umask(mask)
    os.chmod(p, 0o666 & ~mask)
