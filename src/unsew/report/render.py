"""Software rendering of garment meshes to PNG with matplotlib (no OpenGL needed).

Orthographic views of the world frame of FORMATS.md (metres, Y up, body facing +Z, body's left
at +X), flat Lambert shading with some ambient light, two-sided (garments are open surfaces,
so the inside seen through a neckline is lit too, a little darker), hidden surfaces by the
painter's algorithm: all faces of the garment, the body and an optional overlay mesh are sorted
together by depth and drawn far to near as one matplotlib ``PolyCollection``.

Views (the camera looks at the body from):

- ``front``: +Z, looking along -Z; screen right is world +X (the body's left, as in a photo).
- ``back``: -Z, looking along +Z; screen right is world -X.
- ``side``: the body's left (+X), looking along -X; the body faces screen left.
- ``three_quarter``: 40 degrees round from the front towards the body's left, 12 degrees above.

All views of one picture share one scale (metres per pixel), so sizes compare across views.
"""

from __future__ import annotations

import os
import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from unsew.errors import InputError

__all__ = [
    "VIEWS",
    "HEAT_CMAP",
    "view_rotation",
    "project",
    "render_mesh",
    "render_views",
    "render_comparison",
    "Colors",
    "Layout",
]

#: Camera azimuth about +Y from the front [deg] and elevation [deg] of each named view.
VIEWS: dict[str, tuple[float, float]] = {
    "front": (0.0, 0.0),
    "side": (90.0, 0.0),
    "back": (180.0, 0.0),
    "three_quarter": (40.0, 12.0),
}

GARMENT_RGB = (0.30, 0.50, 0.78)
BODY_RGB = (0.80, 0.80, 0.80)
OVERLAY_RGB = (0.85, 0.20, 0.15)
TARGET_RGB = (0.86, 0.50, 0.38)
#: Name of unsew's distance colour map (light yellow = near, dark purple = far); any matplotlib
#: colour map name works too.
HEAT_CMAP = "unsew_heat"
#: Depth bias [m] of the body in the painter's sort: a body face is drawn as if this much further
#: from the camera, so cloth lying a few millimetres over the body is not painted over by body
#: faces whose centroids happen to be nearer (the body "showing through"; measured by
#: ``python -m benchmarks render --bleed``).
BODY_DEPTH_BIAS = 0.02
_INSIDE_DIM = 0.78  # faces seen from their back side (the inside of a garment) are dimmer
_LIGHT = np.array([-0.55, 0.5, 0.75])  # in camera coordinates (right, up, towards the viewer)
_LIGHT = _LIGHT / np.linalg.norm(_LIGHT)
_BG = "white"


@dataclass(frozen=True)
class Colors:
    """How :func:`render_views` colours the meshes.

    Attributes:
        color: RGB in [0, 1] of the garment when it has no vertex values.
        cmap: colour map (a matplotlib name, :data:`HEAT_CMAP` or a Colormap) of the vertex values.
        vmin, vmax: the colour map's range, in the values' unit (default: the data's range).
        colorbar_label: label of the colour bar (put the unit in it).
        overlay_style: ``"ghost"`` (translucent) or ``"wire"`` (a wire frame).
        overlay_color: RGB in [0, 1] of the overlay.
    """

    color: tuple = GARMENT_RGB
    cmap: object = "viridis"
    vmin: float | None = None
    vmax: float | None = None
    colorbar_label: str | None = None
    overlay_style: str = "ghost"
    overlay_color: tuple = OVERLAY_RGB


@dataclass(frozen=True)
class Layout:
    """What a rendered picture shows and how big it is.

    Attributes:
        views: names from :data:`VIEWS`, drawn left to right at one common scale.
        frame: ``"garment"`` frames the garment and overlay (the body is cropped), ``"all"``
            also the body.
        margin: empty border as a fraction of the framed extent [-].
        size_px: (width, height) of the PNG in pixels (default: from the number of views).
        title: a title above the picture, or None.
    """

    views: tuple[str, ...] = ("front", "side")
    frame: str = "garment"
    margin: float = 0.06
    size_px: tuple[int, int] | None = None
    title: str | None = None


def view_rotation(view: str) -> np.ndarray:
    """Rotation (3, 3) float64 whose rows are the camera's right, up and towards-viewer axes
    in world coordinates, for a view name of :data:`VIEWS`.

    Camera coordinates are ``R @ p``: screen x = right, screen y = up, depth = towards the viewer
    (larger is nearer).
    """
    if view not in VIEWS:
        raise InputError(f"unknown view {view!r}; choose one of {', '.join(VIEWS)}")
    az, el = np.deg2rad(VIEWS[view])
    toward = np.array([np.sin(az) * np.cos(el), np.sin(el), np.cos(az) * np.cos(el)])
    right = np.cross(np.array([0.0, 1.0, 0.0]), toward)
    right /= np.linalg.norm(right)
    up = np.cross(toward, right)
    return np.stack([right, up, toward])


def project(verts: np.ndarray, view: str) -> np.ndarray:
    """Orthographic camera coordinates of points.

    verts: positions [m], shape (V, 3). Returns (V, 3) float64 [m]: screen x, screen y, depth
    (larger = nearer the viewer).
    """
    return np.asarray(verts, dtype=np.float64) @ view_rotation(view).T


# --------------------------------------------------------------------------------------------
# input checks


def _np(x):
    """numpy view of an array-like; torch tensors (any device, with grad) are detached first."""
    if hasattr(x, "detach") and hasattr(x, "cpu"):
        x = x.detach().cpu().numpy()
    return np.asarray(x)


def _check_mesh(verts, faces, what: str) -> tuple[np.ndarray, np.ndarray]:
    v = _np(verts).astype(np.float64, copy=False)
    f = _np(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0:
        raise InputError(f"{what} vertices must have shape (V, 3) with V > 0, got {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
        raise InputError(f"{what} faces must have shape (F, 3) with F > 0, got {f.shape}")
    if not np.issubdtype(f.dtype, np.integer):
        if not np.all(np.mod(f, 1) == 0):
            raise InputError(f"{what} faces must hold integer vertex indices")
        f = f.astype(np.int64)
    if f.min() < 0 or f.max() >= len(v):
        raise InputError(f"{what} faces index vertices outside 0..{len(v) - 1}")
    if not np.isfinite(v).all():
        raise InputError(f"{what} vertices contain NaN or infinite coordinates")
    return v, f.astype(np.int64, copy=False)


def _check_pair(pair, what: str):
    if pair is None:
        return None
    try:
        v, f = pair
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a (verts, faces) pair") from None
    return _check_mesh(v, f, what)


# --------------------------------------------------------------------------------------------
# scene description and drawing


@dataclass
class _Layer:
    verts: np.ndarray  # (V, 3) [m]
    faces: np.ndarray  # (F, 3) int
    face_rgb: np.ndarray  # (F, 3) in [0, 1], before shading
    alpha: float = 1.0
    wire: bool = False
    ambient: float = 0.22  # raised for colour-mapped layers so shading does not read as data
    frame: bool = True  # counts for the picture's framing
    depth_bias: float = 0.0  # [m] added to the sort depth (negative: drawn as if further away)


def _face_rgb(verts, faces, vertex_values, color, cmap, norm):
    """Base colour (F, 3) of each face: a flat colour, or the colour map at the face's mean
    vertex value (NaN values get the colour map's 'bad' colour)."""
    if vertex_values is None:
        from matplotlib.colors import to_rgb

        return np.broadcast_to(np.array(to_rgb(color)), (len(faces), 3))
    vals = vertex_values[faces].mean(axis=1)  # (F,)
    rgba = cmap(norm(np.ma.masked_invalid(vals)))
    return rgba[:, :3]


def _split_long_faces(verts, faces, rgb, max_len: float, *, max_faces: int):
    """Bisect faces along their longest edge until no edge is longer than ``max_len`` [m].

    Painter's sorting is by face centroid, which fails where a long face passes behind small
    ones; short faces make it reliable. verts (V, 3) [m], faces (F, 3), rgb (F, 3) per-face colour
    (children inherit it). Stops early rather than exceed ``max_faces``. New vertices are not
    shared between neighbours (T-junctions do not matter for drawing).
    """
    for _ in range(12):
        tri = verts[faces]  # (F, 3, 3)
        el = np.linalg.norm(tri[:, [1, 2, 0]] - tri, axis=2)  # (F, 3): edge i runs i -> i+1
        longest = el.max(axis=1)
        sel = longest > max_len
        n = int(sel.sum())
        if n == 0 or len(faces) + n > max_faces:
            break
        k = el[sel].argmax(axis=1)  # (n,) the longest edge of each selected face
        f = faces[sel]
        rows = np.arange(n)[:, None]
        f = f[rows, (k[:, None] + np.arange(3)) % 3]  # rotate so the longest edge is a -> b
        a, b, c = f[:, 0], f[:, 1], f[:, 2]
        m = np.arange(len(verts), len(verts) + n)
        verts = np.concatenate([verts, 0.5 * (verts[a] + verts[b])])
        kids = np.concatenate([np.stack([a, m, c], 1), np.stack([m, b, c], 1)])
        faces = np.concatenate([faces[~sel], kids])
        rgb = np.concatenate([rgb[~sel], rgb[sel], rgb[sel]])
    return verts, faces, rgb


def _shade(cam_tri: np.ndarray, base_rgb: np.ndarray, ambient: float) -> np.ndarray:
    """Two-sided Lambert shading. cam_tri: (F, 3, 3) camera coordinates [m]; base_rgb: (F, 3)
    in [0, 1]; ambient: the light every face gets, in [0, 1]. Returns (F, 3) in [0, 1]."""
    n = np.cross(cam_tri[:, 1] - cam_tri[:, 0], cam_tri[:, 2] - cam_tri[:, 0])  # (F, 3)
    norm = np.linalg.norm(n, axis=1, keepdims=True)
    n = n / np.maximum(norm, 1e-30)
    facing = n[:, 2] >= 0  # the outward (CCW) side faces the camera
    n = np.where(facing[:, None], n, -n)  # two-sided: light the side that is seen
    lam = np.clip(n @ _LIGHT, 0.0, 1.0)
    # a soft head-light term keeps silhouettes from going black
    k = ambient + (1.0 - ambient) * (0.8 * lam + 0.2 * n[:, 2])
    k = np.where(facing, k, k * _INSIDE_DIM)
    return np.clip(base_rgb * k[:, None], 0.0, 1.0)


def _scene_polys(layers: list[_Layer], view: str):
    """Depth-sorted polygons and colours for one view.

    Returns (polys (F, 3, 2) [m], facecolors (F, 4), edgecolors (F, 4), bbox (xmin, xmax, ymin,
    ymax) [m] of the framed layers). Opaque faces are stroked in their own colour (closing
    the hairline antialiasing gaps between neighbours), translucent ones not at all (alpha 0),
    wire faces only stroked; one line width serves all, which keeps matplotlib fast.
    """
    R = view_rotation(view)
    polys, depth, fc, ec = [], [], [], []
    lo = np.array([np.inf, np.inf])
    hi = -lo
    for L in layers:
        cam = L.verts @ R.T  # (V, 3)
        tri = cam[L.faces]  # (F, 3, 3)
        polys.append(tri[:, :, :2])
        depth.append(tri[:, :, 2].mean(axis=1) + L.depth_bias)  # sort key: centroid depth
        if L.frame:
            lo = np.minimum(lo, cam[:, :2].min(axis=0))
            hi = np.maximum(hi, cam[:, :2].max(axis=0))
        rgb = _shade(tri, L.face_rgb, L.ambient)
        F = len(L.faces)
        rgba = np.concatenate([rgb, np.full((F, 1), L.alpha)], axis=1)
        clear = np.zeros((F, 4))
        if L.wire:
            f4, e4 = clear, rgba
        else:
            f4, e4 = rgba, (rgba if L.alpha >= 1.0 else clear)
        fc.append(f4)
        ec.append(e4)
    order = np.argsort(np.concatenate(depth), kind="stable")  # far to near
    if not np.isfinite(lo).all():  # nothing framed: frame everything
        allp = np.concatenate(polys).reshape(-1, 2)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
    return (
        np.concatenate(polys)[order],
        np.concatenate(fc)[order],
        np.concatenate(ec)[order],
        (lo[0], hi[0], lo[1], hi[1]),
    )


def _layers(verts, faces, *, vertex_values, colors: Colors, scale, body, overlay, frame) -> list[_Layer]:
    """The layers of one scene: the body (light grey), the garment (``colors.color``, or its
    vertex values through scale = (cmap, norm)), the overlay as ``colors`` says; faces far
    longer than the garment's typical edge split."""
    cmap, norm = scale
    layers = []
    if body is not None:
        bv, bf = body
        layers.append(
            _Layer(
                bv,
                bf,
                _face_rgb(bv, bf, None, BODY_RGB, None, None),
                frame=(frame == "all"),
                depth_bias=-BODY_DEPTH_BIAS,
            )
        )
    layers.append(
        _Layer(
            verts,
            faces,
            _face_rgb(verts, faces, vertex_values, colors.color, cmap, norm),
            ambient=0.22 if vertex_values is None else 0.55,
        )
    )
    if overlay is not None:
        ov, of = overlay
        rgb = _face_rgb(ov, of, None, colors.overlay_color, None, None)
        if colors.overlay_style == "wire":
            layers.append(_Layer(ov, of, rgb, alpha=0.9, wire=True))
        else:
            layers.append(_Layer(ov, of, rgb, alpha=0.28))
    # faces much longer than the garment's typical edge get split (see _split_long_faces)
    el = np.linalg.norm(verts[faces[:, [1, 2, 0]]] - verts[faces], axis=2)
    max_len = max(3.0 * float(np.median(el)), 1e-3)
    for L in layers:
        if not L.wire:
            L.verts, L.faces, L.face_rgb = _split_long_faces(
                L.verts, L.faces, np.asarray(L.face_rgb), max_len, max_faces=3 * len(L.faces) + 50_000
            )
    return layers


# --------------------------------------------------------------------------------------------
# figure layout


def _px_axes(fig, x0, y0, w, h, W, H):
    """An axes at pixel box (x0, y0 from the bottom-left, w, h) of a W x H figure, no decoration."""
    ax = fig.add_axes((x0 / W, y0 / H, w / W, h / H))
    ax.set_axis_off()
    return ax


def _scale(drawn, cell_w, cell_h, *, row_title, pad, margin) -> float:
    """One scale for all cells [pixels per metre]: the largest at which every cell's framed
    extent, grown by ``margin``, fits its cell."""
    scale = np.inf
    for row in drawn:
        for *_, (x0, x1, y0, y1) in row:
            dx = max(x1 - x0, 1e-9) * (1 + 2 * margin)
            dy = max(y1 - y0, 1e-9) * (1 + 2 * margin)
            scale = min(scale, (cell_w - 2 * pad) / dx, (cell_h - row_title - 2 * pad) / dy)
    return scale


def _colorbar(fig, W, H, scale) -> None:
    """A horizontal colour bar at the bottom of a W x H pixel figure; scale = (cmap, norm,
    extend, label)."""
    import matplotlib.cm as cm

    cmap, norm, extend, label = scale
    cw = min(0.6 * W, 420)
    cax = fig.add_axes(((W - cw) / 2 / W, 40 / H, cw / W, 12 / H))
    sm = cm.ScalarMappable(norm=norm, cmap=cmap)
    cb = fig.colorbar(sm, cax=cax, orientation="horizontal", extend=extend)
    cb.set_label(label or "", fontsize=9)
    cb.ax.tick_params(labelsize=8)


def _render(path_png, scenes: list[list[_Layer]], *, titles, layout: Layout, scale, dpi=100):
    """Draw a grid (rows = scenes, columns = layout.views) into one PNG of exactly
    layout.size_px pixels; scale = (cmap, norm, extend, colour bar label), cmap and norm None
    for no colour bar."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    views, size_px, title = layout.views, layout.size_px, layout.title
    W, H = int(size_px[0]), int(size_px[1])
    if W < 32 or H < 32:
        raise InputError(f"size_px must be at least 32 x 32 pixels, got {size_px}")
    fig = Figure(figsize=(W / dpi, H / dpi), dpi=dpi, facecolor=_BG)
    FigureCanvasAgg(fig)

    top = 34 if title else 6
    row_title = 22 if (any(titles) or len(views) > 1) else 0
    bottom = 66 if scale[1] is not None else 6
    nr, nc = len(scenes), len(views)
    cell_w = (W - 12) / nc
    cell_h = (H - top - bottom) / nr
    if cell_h - row_title < 16 or cell_w < 16:
        raise InputError(f"size_px {size_px} is too small for {nr} x {nc} views")
    pad = 6
    drawn = [[_scene_polys(sc, v) for v in views] for sc in scenes]
    px_per_m = _scale(drawn, cell_w, cell_h, row_title=row_title, pad=pad, margin=layout.margin)
    aw, ah = cell_w - 2 * pad, cell_h - row_title - 2 * pad
    for r, row in enumerate(drawn):
        for c, (polys, fc, ec, (x0, x1, y0, y1)) in enumerate(row):
            ax = _px_axes(fig, 6 + c * cell_w + pad, bottom + (nr - 1 - r) * cell_h + pad, aw, ah, W, H)
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            ax.set_xlim(cx - aw / px_per_m / 2, cx + aw / px_per_m / 2)
            ax.set_ylim(cy - ah / px_per_m / 2, cy + ah / px_per_m / 2)
            pc = PolyCollection(
                polys, facecolors=fc, edgecolors=ec, linewidths=72.0 / dpi, antialiaseds=True, closed=True
            )
            ax.add_collection(pc, autolim=False)
            label = titles[r] if titles[r] else ""
            if len(views) > 1 or label:
                text = f"{label} — {views[c]}" if (label and len(views) > 1) else (label or views[c])
                x_t, y_t = (6 + (c + 0.5) * cell_w) / W, (bottom + (nr - r) * cell_h - 4) / H
                fig.text(x_t, y_t, text, ha="center", va="top", fontsize=10, color="#333333")
    if title:
        fig.text(0.5, 1 - 8 / H, title, ha="center", va="top", fontsize=13, weight="bold")
    if scale[1] is not None:
        _colorbar(fig, W, H, scale)
    path = Path(path_png)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(os.fspath(path), dpi=dpi, facecolor=_BG, format="png")
    return path


def _extend(lo_out: bool, hi_out: bool) -> str:
    """The colour bar's arrows: which ends the data ran past."""
    return (
        {(False, False): "neither", (True, False): "min", (False, True): "max"}[(lo_out, hi_out)]
        if not (lo_out and hi_out)
        else "both"
    )


def _colormap(vertex_values, n_verts, *, cmap, vmin, vmax):
    """(values (V,) float64, cmap, norm, lo_out, hi_out) or all None when no values are given."""
    if vertex_values is None:
        return None, None, None, False, False
    import matplotlib
    from matplotlib.colors import Normalize

    vals = _np(vertex_values).astype(np.float64).reshape(-1)
    if vals.shape != (n_verts,):
        raise InputError(
            f"vertex_values must have shape ({n_verts},) (one per vertex), got {np.shape(vertex_values)}"
        )
    finite = vals[np.isfinite(vals)]
    lo = float(vmin) if vmin is not None else (float(finite.min()) if finite.size else 0.0)
    hi = float(vmax) if vmax is not None else (float(finite.max()) if finite.size else 1.0)
    if not hi > lo:
        hi = lo + 1.0 if lo == hi else lo
        if not hi > lo:
            raise InputError(f"vmin {vmin} must be below vmax {vmax}")
    if isinstance(cmap, str) and cmap == HEAT_CMAP:
        # light yellow (near) to dark purple (far), both ends of inferno_r trimmed: the lightest
        # would vanish on white and the darkest would read as shadow
        from matplotlib.colors import ListedColormap

        cm_ = ListedColormap(matplotlib.colormaps["inferno_r"](np.linspace(0.1, 0.85, 256)), name=HEAT_CMAP)
    else:
        cm_ = matplotlib.colormaps[cmap] if isinstance(cmap, str) else cmap
    cm_ = cm_.with_extremes(bad=(0.6, 0.6, 0.6))
    lo_out = bool(finite.size and finite.min() < lo)
    hi_out = bool(finite.size and finite.max() > hi)
    return vals, cm_, Normalize(vmin=lo, vmax=hi, clip=True), lo_out, hi_out


# --------------------------------------------------------------------------------------------
# public entry points


def _check_layout(layout: Layout) -> tuple[str, ...]:
    """The layout's views as a tuple; InputError on an unknown view or frame."""
    views = tuple(layout.views)
    if not views:
        raise InputError("views must name at least one view")
    for v in views:
        view_rotation(v)  # validates the name
    if layout.frame not in ("garment", "all"):
        raise InputError(f"frame must be 'garment' or 'all', got {layout.frame!r}")
    return views


def render_views(
    path_png: str | os.PathLike,
    verts: np.ndarray,
    faces: np.ndarray,
    *,
    vertex_values: np.ndarray | None = None,
    body: tuple[np.ndarray, np.ndarray] | None = None,
    overlay: tuple[np.ndarray, np.ndarray] | None = None,
    colors: Colors = Colors(),
    layout: Layout = Layout(),
) -> Path:
    """Render a mesh from several views side by side into one PNG; returns the PNG's path.

    verts: garment vertex positions [m], shape (V, 3), float64, world frame (Y up, front +Z).
    faces: triangles, shape (F, 3), int, indices into verts.
    vertex_values: optional per-vertex scalar, shape (V,), float (e.g. distance to the target
        [mm]); faces are coloured by ``colors.cmap`` at their mean vertex value between
        ``colors.vmin`` and ``colors.vmax`` (default: the data's range), NaN in grey, with a
        colour bar labelled ``colors.colorbar_label``. Without values the garment is ``colors.color``.
    body: optional (verts (Vb, 3) [m], faces (Fb, 3)) drawn in light grey, hidden surfaces
        resolved together with the garment.
    overlay: optional (verts (Vo, 3) [m], faces (Fo, 3)), e.g. the target, drawn in
        ``colors.overlay_color`` either as a translucent ``"ghost"`` or a ``"wire"`` frame.
    colors: :class:`Colors`. layout: :class:`Layout` (views, frame, margin, size, title); its
        size_px defaults to 420 x 560 per view.
    """
    views = _check_layout(layout)
    verts, faces = _check_mesh(verts, faces, "garment")
    body = _check_pair(body, "body")
    overlay = _check_pair(overlay, "overlay")
    if colors.overlay_style not in ("ghost", "wire"):
        raise InputError(f"overlay_style must be 'ghost' or 'wire', got {colors.overlay_style!r}")
    vals, cm_, norm, lo_out, hi_out = _colormap(
        vertex_values, len(verts), cmap=colors.cmap, vmin=colors.vmin, vmax=colors.vmax
    )
    size_px = layout.size_px
    if size_px is None:
        size_px = (420 * len(views), 560 + (52 if vals is not None else 0) + (28 if layout.title else 0))
    layers = _layers(
        verts,
        faces,
        vertex_values=vals,
        colors=colors,
        scale=(cm_, norm),
        body=body,
        overlay=overlay,
        frame=layout.frame,
    )
    return _render(
        path_png,
        [layers],
        titles=[None],
        layout=dataclasses.replace(layout, views=views, size_px=size_px),
        scale=(cm_, norm, _extend(lo_out, hi_out), colors.colorbar_label),
    )


def render_mesh(
    path_png: str | os.PathLike,
    verts: np.ndarray,
    faces: np.ndarray,
    *,
    view: str = "front",
    size_px: tuple[int, int] = (600, 800),
    **style,
) -> Path:
    """Render one orthographic view of a mesh to a PNG of exactly ``size_px`` pixels.

    ``view``: ``"front"``, ``"side"``, ``"back"`` or ``"three_quarter"``; ``style``: the
    keyword arguments ``vertex_values``, ``body``, ``overlay`` of :func:`render_views` and the
    fields of :class:`Colors` and :class:`Layout` (frame, margin, title) by name. Returns the
    PNG's path.
    """
    meshes = {k: style.pop(k) for k in ("vertex_values", "body", "overlay") if k in style}
    colors = Colors(**{f.name: style.pop(f.name) for f in dataclasses.fields(Colors) if f.name in style})
    layout = Layout(views=(view,), size_px=size_px, **style)
    return render_views(path_png, verts, faces, colors=colors, layout=layout, **meshes)


def _heat_scale(distance_mm, n_verts: int, vmax_mm):
    """_colormap of the distances [mm] on the heat map from 0 to vmax_mm (default: their
    98th percentile)."""
    vmax = vmax_mm
    if distance_mm is not None and vmax is None:
        d = _np(distance_mm).astype(np.float64)
        d = d[np.isfinite(d)]
        vmax = float(np.percentile(d, 98)) if d.size else 1.0
        vmax = vmax if vmax > 0 else 1.0
    return _colormap(
        distance_mm, n_verts, cmap=HEAT_CMAP, vmin=0.0 if distance_mm is not None else None, vmax=vmax
    )


def render_comparison(
    path_png: str | os.PathLike,
    target: tuple[np.ndarray, np.ndarray],
    result: tuple[np.ndarray, np.ndarray],
    *,
    distance_mm: np.ndarray | None = None,
    vmax_mm: float | None = None,
    body: tuple[np.ndarray, np.ndarray] | None = None,
    labels: tuple[str, str] = ("target", "result"),
    layout: Layout = Layout(frame="all"),
) -> Path:
    """Target (top row) and result (bottom row) from the same views at one common scale.

    target, result: (verts (V, 3) [m], faces (F, 3)) pairs. distance_mm: optional per-vertex
    distance of the result to the target [mm], shape (V_result,); colours the result with
    the :data:`HEAT_CMAP` heat map from 0 to ``vmax_mm`` (default: the 98th percentile). body:
    optional (verts, faces) drawn under both. layout: :class:`Layout`; its frame ``"all"``
    (default) frames the whole body too, ``"garment"`` only target and result; its size_px
    defaults to 360 x 1000 per view. Returns the PNG's path.
    """
    views = _check_layout(layout)
    tv, tf = _check_mesh(*_unpair(target, "target"), "target")
    rv, rf = _check_mesh(*_unpair(result, "result"), "result")
    body = _check_pair(body, "body")
    vals, cm_, norm, lo_out, hi_out = _heat_scale(distance_mm, len(rv), vmax_mm)
    size_px = layout.size_px
    if size_px is None:
        size_px = (360 * len(views), 2 * 500 + (58 if vals is not None else 0) + (34 if layout.title else 0))
    common = dict(scale=(cm_, norm), body=body, overlay=None, frame=layout.frame)
    top = _layers(tv, tf, vertex_values=None, colors=Colors(color=TARGET_RGB), **common)
    bot = _layers(rv, rf, vertex_values=vals, colors=Colors(color=GARMENT_RGB), **common)
    # frame both rows on the union of target and result so the rows line up
    for layers, other in ((top, (rv, rf)), (bot, (tv, tf))):
        layers.append(_Layer(other[0], other[1][:0], np.zeros((0, 3))))
    return _render(
        path_png,
        [top, bot],
        titles=list(labels),
        layout=dataclasses.replace(layout, views=views, size_px=size_px),
        scale=(cm_, norm, _extend(lo_out, hi_out), "distance to target [mm]"),
    )


def _unpair(pair, what):
    try:
        v, f = pair
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a (verts, faces) pair") from None
    return v, f
