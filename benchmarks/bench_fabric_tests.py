"""Does unsew's cloth simulator pass the fabric laboratory's tests (Cusick drape, Peirce cantilever)?

Two standard fabric tests, simulated with unsew's own static solver (``unsew.sim.drape_static``,
its membrane and hinge-bending energies, areal density and gravity), and compared with their
analytic answer (cantilever) and with published figures for real fabrics (docs/fabric_tests.md):

- Cantilever (Peirce 1930; ASTM D1388, BS 3356): a 2.5 cm wide strip clamped flat at an edge
  overhangs by l; the chord from the edge to its tip makes an angle phi below the horizontal. The
  instrument reads the overhang l at which phi = 41.5 deg and reports the bending length c = l/2
  and the flexural rigidity G = w g c^3 (w the areal density [kg/m^2]). We find that overhang for
  the simulated strip (secant on l), compare it with the exact heavy elastica's (solved here by
  shooting), and report the rigidity the instrument would read, G_read / D (1 for a bending model of
  the right scale and Peirce's approximation; the exact elastica alone gives its own ratio).
- Drape (Cusick 1968; BS 5058, ISO 9073-9): a 30 cm disc of fabric is clamped between two 18 cm
  discs and hangs under gravity. DC = (shadow area - support area) / (specimen area - support
  area), the shadow being the vertical projection of the draped specimen; nodes: the number of
  folds around the hem (local maxima of the shadow's outline radius). The clamp is modelled by
  pinning every vertex within the support's radius; no contact (nothing is below the specimen).
  A small seeded random lift of the free vertices breaks the axial symmetry; the equilibrium
  reached depends on it (as a real specimen's node count depends on how it was laid down).

Prints both tables, each fabric's published bending and weight figures beside what the
simulation makes of them, writes figures (``--figures``: the
draped specimen from above with the disc, the strip's profile with the 41.5 deg line) and, with
``--record``, the tables as benchmarks/results/fabric_{cantilever,drape}.json.

Run: python -m benchmarks fabric_tests [--small] [--figures docs/figures] [--record] [--seeds 3]
     python -m benchmarks fabric_tests --newton-cantilever (newton's settling, _newton_cantilever.py)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
RESULTS = HERE / "results"
G = 9.81  #: gravity [m/s^2]
PEIRCE_ANGLE = math.radians(41.5)  #: the cantilever tester's incline [rad]

#: 1 gf*cm^2/cm (KES bending rigidity unit) in N*m
KES_B = 9.80665e-5


@dataclass(frozen=True)
class Fabric:
    """A fabric to test: name, bending rigidity D [N*m], areal density w [kg/m^2], membrane
    (H00, H01, H11, H22) [N/m], and where its figures come from (``source``)."""

    name: str
    bend: float
    density: float
    membrane: tuple[float, float, float, float]
    source: str
    #: the source's own Cusick figures for this fabric, when it gives them: the measured DC [%]
    #: and the DC its authors' simulator (CLO3D) made of the same inputs [%]
    dc_measured: float | None = None
    dc_other_sim: float | None = None

    def gamma(self):
        import torch

        return torch.tensor([*self.membrane, self.bend], dtype=torch.float64)

    @property
    def bending_length(self) -> float:
        """c = (D / (w g))^(1/3) [m], the cantilever's bending length for this D and w."""
        return (self.bend / (self.density * G)) ** (1.0 / 3.0)


def library_fabrics() -> list[Fabric]:
    """unsew's material library (unsew.sim.MATERIALS), its KES-based bending and weights."""
    from unsew.sim import MATERIALS

    out = []
    for name in ("silk", "jersey", "polyester", "cotton", "wool", "denim"):
        m = MATERIALS[name]
        out.append(
            Fabric(
                name=f"unsew {name}",
                bend=m.bend,
                density=m.density,
                membrane=(m.h00, m.h01, m.h11, m.h22),
                source="unsew.sim.MATERIALS (KES B, weight as sold)",
            )
        )
    return out


#: Wang, O'Brien and Ramamoorthi 2011 ("Data-driven elastic models for cloth", the Berkeley
#: Garment Library's ARCSim material files): density [kg/m^2] and the first bending sample
#: (bending[0][0], warp direction, lowest curvature), ARCSim's hinge coefficient ke. ARCSim's
#: hinge energy is ke |e|^2/(2 (A1+A2)) theta^2/4, which on a grid bent to a cylinder stores
#: ke/8 kappa^2 per unit area: D = ke/4 in plate terms (docs/fabric_tests.md).
WANG_2011 = {
    "gray-interlock": (0.187, 23.191698e-6),
    "camel-ponte-roma": (0.284, 36.34897e-6),
    "11oz-black-denim": (0.324, 64.196457e-6),
    "pink-ribbon-brown": (0.228, 117.10344e-6),
}


def wang_fabrics(names=None) -> list[Fabric]:
    """Fabrics of Wang et al. 2011 (D = ke/4, their density) with unsew's cotton membrane."""
    from unsew.sim import MATERIALS

    m = MATERIALS["cotton"]
    return [
        Fabric(
            name=f"Wang11 {n}",
            bend=ke / 4.0,
            density=rho,
            membrane=(m.h00, m.h01, m.h11, m.h22),
            source="Wang et al. 2011, ARCSim material file: density, bending[0][0]/4",
        )
        for n, (rho, ke) in WANG_2011.items()
        if names is None or n in names
    ]


#: Petrak et al. 2025 (Sustainability 17(4):1388, doi:10.3390/su17041388, CC-BY 4.0): six woven
#: dress fabrics, their mass, KES-FB measurements converted to CLO3D's inputs, and the Cusick drape
#: coefficient measured (30 cm specimen on an 18 cm support) and simulated in CLO3D, as transcribed
#: from the paper's Tables 1, 2, 4 and 5 in KAFKA2306/image2outfit
#: config/materials/kes-woven-fabrics-2025.v1.json (commit 1e4a63f). Per fabric: mass [g/m^2],
#: bending warp, weft [CLO: g mm^2/s^2 = 1e-9 N m], stretch warp, weft and shear [CLO: g/s^2 =
#: 1e-3 N/m], DC measured and DC in CLO3D [-].
PETRAK_2025 = {
    "m1 polyester twill": (135.17, (1950, 610), (477226, 458614, 41000), 0.223, 0.349),
    "m2 polyester plain": (83.66, (850, 330), (471944, 373515, 46000), 0.228, 0.313),
    "m3 wool-polyester-elastane twill": (178.70, (2140, 2000), (449656, 439815, 50000), 0.349, 0.404),
    "m4 polyester-viscose-elastane twill": (286.13, (2970, 2400), (403447, 401762, 61000), 0.286, 0.323),
    "m5 polyester-elastane plain": (242.00, (3220, 3880), (407166, 415023, 57000), 0.443, 0.438),
    "m6 cotton-polyester-elastane twill": (253.36, (7430, 3700), (473860, 404746, 126000), 0.549, 0.613),
}


def petrak_fabrics(*, membrane: str = "source") -> list[Fabric]:
    """The fabrics of Petrak et al. 2025 (:data:`PETRAK_2025`): D the mean of the warp and weft
    bending [N*m] (unsew's bending is isotropic), their mass, and with ``membrane`` "source" their
    stretch and shear read as H00, H11, H22 [N/m] (H01 = 0), or "cotton" unsew's cotton membrane."""
    from unsew.sim import MATERIALS

    m = MATERIALS["cotton"]
    out = []
    for n, (gsm, bends, (sw, sf, sh), dc, dc_clo) in PETRAK_2025.items():
        mem = (sw * 1e-3, 0.0, sf * 1e-3, sh * 1e-3) if membrane == "source" else (m.h00, m.h01, m.h11, m.h22)
        out.append(
            Fabric(
                name=f"Petrak25 {n}" + ("" if membrane == "source" else ", cotton membrane"),
                bend=1e-9 * float(np.mean(bends)),
                density=gsm * 1e-3,
                membrane=mem,
                source="Petrak et al. 2025, Tables 1, 2, 4, 5 (via image2outfit's transcription)",
                dc_measured=100 * dc,
                dc_other_sim=100 * dc_clo,
            )
        )
    return out


def newton_target_fabric() -> Fabric:
    """The fabric of the foreign benchmark's newton targets (benchmarks/foreign/newton_drape.py
    SETTINGS): density 0.2 kg/m^2, membrane (tri_aniso_ke) 2000, 0, 2000, 200 N/m, and D the
    mean over three bend directions of the plate rigidity its Style3D bending stands for on a
    10 mm mesh (:func:`style3d_bending_rows`)."""
    row = style3d_bending_rows(edges=(0.01,))[1]
    d = float(np.mean([v for k, v in row.items() if k.startswith("axis")])) * 1e-6
    return Fabric(
        name="newton targets' fabric",
        bend=d,
        density=0.2,
        membrane=(2000.0, 0.0, 2000.0, 200.0),
        source="benchmarks/foreign/newton_drape.py SETTINGS; D from style3d_bending_rows",
    )


# -- the heavy elastica (exact cantilever) -----------------------------------------------------


def elastica(lam: float, n: int = 2001):
    """Shape of a heavy cantilever of overhang lam (in units of c = (D/(w g))^(1/3)), clamped
    horizontal at s = 0: theta'' = -(lam - s) cos theta, theta(0) = 0, theta'(lam) = 0 (theta the
    slope angle below the horizontal). Returns (x, y) (n,) in units of c, y downward positive."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    def rhs(s, z):
        th, k, x, y = z
        # the physical slope lies in [0, pi/2]; clipping it there in the load term keeps the end
        # curvature monotone in the root curvature for the shooting (a trial that turns up or
        # past the vertical does not wrap around)
        load = math.cos(min(max(th, 0.0), math.pi / 2))
        return [k, -(lam - s) * load, math.cos(th), math.sin(th)]

    def end_curv(k0):
        sol = solve_ivp(rhs, (0.0, lam), [0.0, k0, 0.0, 0.0], rtol=1e-11, atol=1e-12)
        return sol.y[1, -1]

    # the root curvature lies between 0 and the small-deflection value lam^2/2 (gravity's moment
    # only drops as the strip turns down); a little above it for the bracket's sign
    k0 = brentq(end_curv, 0.0, lam * lam / 2.0 * 1.01, xtol=1e-13)
    s = np.linspace(0.0, lam, n)
    sol = solve_ivp(rhs, (0.0, lam), [0.0, k0, 0.0, 0.0], t_eval=s, rtol=1e-11, atol=1e-12)
    return sol.y[2], sol.y[3]


def chord_angle(x: float, y: float) -> float:
    """Angle [rad] below the horizontal of the chord from the edge to a tip at (x, y down)."""
    return math.atan2(y, x)


def elastica_overhang(angle: float = PEIRCE_ANGLE) -> float:
    """Overhang lam = l/c at which the exact elastica's chord angle is ``angle`` [rad]."""
    from scipy.optimize import brentq

    def f(lam):
        x, y = elastica(lam)
        return chord_angle(x[-1], y[-1]) - angle

    return brentq(f, 0.5, 4.0, xtol=1e-10)


def peirce_ratio(angle: float = PEIRCE_ANGLE) -> float:
    """Peirce's c / l = (cos(phi/2) / (8 tan phi))^(1/3) at chord angle phi [rad]."""
    return (math.cos(angle / 2.0) / (8.0 * math.tan(angle))) ** (1.0 / 3.0)


# -- the simulated cantilever ----------------------------------------------------------------


def strip_mesh(overhang: float, *, width: float = 0.025, edge: float, clamp: float = 0.01, kind: str):
    """A strip [-clamp, overhang] x [0, width] [m]. kind "grid": the quads' diagonals alternate
    (edges across the strip on every column); "tri": an unstructured Delaunay mesh (triangle).
    Returns uv (V, 2) [m] float64, faces (F, 3) int64 (counter-clockwise)."""
    if kind == "grid":
        from unsew.sim.meshes import grid_sheet

        nx = max(2, round((overhang + clamp) / edge))
        ny = max(1, round(width / edge))
        # put a column exactly on the edge x = 0
        nc = max(1, round(clamp / (overhang + clamp) * nx))
        xs = np.concatenate([np.linspace(-clamp, 0.0, nc + 1)[:-1], np.linspace(0.0, overhang, nx - nc + 1)])
        uv, f = grid_sheet(len(xs) - 1, ny, 1.0, width)
        uv[:, 0] = xs[np.round(uv[:, 0] * (len(xs) - 1)).astype(int)]
        return uv, f
    import triangle

    corners = np.array([[-clamp, 0], [0, 0], [overhang, 0], [overhang, width], [0, width], [-clamp, width]])
    segs = np.array([[i, (i + 1) % 6] for i in range(6)] + [[1, 4]])
    amax = math.sqrt(3) / 4 * edge * edge
    t = triangle.triangulate({"vertices": corners, "segments": segs}, f"pq30a{amax:.12f}")
    return np.asarray(t["vertices"], float), np.asarray(t["triangles"], np.int64)


def simulate_strip(fab: Fabric, overhang: float, *, edge: float, kind: str, mesh_at: float | None = None):
    """Static equilibrium of the strip clamped on x <= 0 (pinned), overhang [m]. With ``mesh_at``
    [m] the strip is meshed at that overhang and its free part stretched along x to ``overhang``
    (one mesh for every overhang tried: the chord angle then varies smoothly with the overhang).

    Returns uv (V, 2), x (V, 3) [m] and the tip chord angle [rad] (mean of the tip row)."""
    import torch

    from unsew.sim import Cloth, PlaneSDF, SimModel, StaticSettings, drape_static

    uv, f = strip_mesh(mesh_at or overhang, edge=edge, kind=kind)
    uv[:, 0] = np.where(uv[:, 0] > 0, uv[:, 0] * overhang / (mesh_at or overhang), uv[:, 0])
    pinned = uv[:, 0] <= 1e-12
    model = SimModel.build(f, f, pinned=pinned)
    # start from the exact elastica of this D and w (the stable cantilever's equilibrium is
    # unique, so the start only saves Newton iterations: from flat they take about a hundred)
    c = fab.bending_length
    s = np.linspace(0.0, overhang / c, 401)
    ex, ey = elastica(overhang / c, n=401)
    u = np.clip(uv[:, 0], 0.0, None) / c
    xs = np.where(uv[:, 0] > 0, np.interp(u, s, ex) * c, uv[:, 0])
    x0 = torch.as_tensor(np.c_[xs, -np.interp(u, s, ey) * c, uv[:, 1]])
    far = PlaneSDF(point=(0.0, -10.0, 0.0))  # nothing to touch
    x = drape_static(
        model,
        x0,
        far,
        Cloth(torch.as_tensor(uv), fab.gamma(), fab.density),
        settings=StaticSettings(max_iter=200),
    ).numpy()
    tip = uv[:, 0] >= overhang - 1e-9
    return uv, x, chord_angle(float(x[tip, 0].mean()), float(-x[tip, 1].mean()))


def cantilever_overhang(fab: Fabric, *, edge: float, kind: str, tol: float = 1e-4):
    """Overhang [m] at which the simulated strip's chord reaches 41.5 deg, with the last strip
    simulated (uv, x). One mesh, made at the exact elastica's overhang and stretched to each one
    tried; secant steps kept inside a bracket of the crossing (bisection when a step leaves it)."""
    lam = elastica_overhang()
    c = fab.bending_length
    pts = []  # (overhang, angle - 41.5 deg)

    def probe(over):
        uv, x, phi = simulate_strip(fab, over, edge=edge, kind=kind, mesh_at=lam * c)
        pts.append((over, phi - PEIRCE_ANGLE))
        return uv, x

    uv, x = probe(lam * c)
    step = 1.05 if pts[-1][1] < 0 else 1 / 1.05
    while len(pts) < 12 and (pts[-1][1] < 0) == (pts[0][1] < 0):  # walk out to a bracket
        uv, x = probe(pts[-1][0] * step)
    for _ in range(10):
        lo = max((p for p in pts if p[1] < 0), key=lambda p: p[0], default=None)
        hi = min((p for p in pts if p[1] >= 0), key=lambda p: p[0], default=None)
        if abs(pts[-1][1]) < tol or lo is None or hi is None:
            break
        (l0, p0), (l1, p1) = pts[-2], pts[-1]
        nxt = l1 - p1 * (l1 - l0) / (p1 - p0) if p1 != p0 else 0.0
        if not (min(lo[0], hi[0]) < nxt < max(lo[0], hi[0])):
            nxt = 0.5 * (lo[0] + hi[0])
        uv, x = probe(nxt)
    return pts[-1][0], uv, x


def cantilever_rows(cases, *, log=print):
    """One row per case (fabric, mesh kind, edge [m]): input D, the elastica's and the
    simulation's overhang, the instrument's reading G = w g (l/2)^3 and its ratio to D, and the
    effective rigidity of the discrete strip, (l_sim / l_elastica)^3 D."""
    lam = elastica_overhang()
    rows, shapes = [], {}
    for fab, kind, edge in cases:
        c = fab.bending_length
        t = time.perf_counter()
        l_sim, uv, x = cantilever_overhang(fab, edge=edge, kind=kind)
        g_read = fab.density * G * (l_sim / 2.0) ** 3
        rows.append(
            {
                "fabric": fab.name,
                "mesh": f"{kind} {edge * 1000:.1f} mm",
                "D input uN m": fab.bend * 1e6,
                "w g/m2": fab.density * 1000,
                "c input cm": c * 100,
                "overhang elastica cm": lam * c * 100,
                "overhang sim cm": l_sim * 100,
                "G read uN m": g_read * 1e6,
                "G read / D": g_read / fab.bend,
                "D effective / D": (l_sim / (lam * c)) ** 3,
            }
        )
        shapes.setdefault((fab.name, kind), (uv, x, l_sim))
        log(
            f"  cantilever {fab.name} {kind} {edge * 1000:.1f} mm: overhang {l_sim * 100:.2f} cm "
            f"({time.perf_counter() - t:.1f} s)"
        )
    return rows, shapes


def linear_strip_rows(fab: Fabric, cells=((6, 1), (6, 5), (6, 10), (12, 5), (12, 10), (24, 10))):
    """Small deflections: a strip of ``fab``'s weight a thousand times stiffer (so it barely
    bends), overhang 3 cm, width 2.5 cm, on grids of nx x ny cells (and one clamp column):
    tip drop against the beam formula w g l^4 / (8 D), and the hinge-chain's own answer (only
    the hinges across the strip bending, lumped masses: the trapezoid rule's O(h^2) error)."""
    import torch

    from unsew.sim import Cloth, PlaneSDF, SimModel, drape_static
    from unsew.sim.energies.bending import dihedral_angle
    from unsew.sim.meshes import grid_sheet

    L, W = 0.03, 0.025
    stiff = dataclasses.replace(fab, bend=1000 * fab.bend)
    beam = stiff.density * G * L**4 / (8 * stiff.bend)
    rows = []
    for nx, ny in cells:
        h = L / nx
        uv, f = grid_sheet(nx + 1, ny, L + h, W)
        uv[:, 0] -= h
        model = SimModel.build(f, f, pinned=uv[:, 0] <= 1e-12)
        x0 = torch.as_tensor(np.c_[uv[:, 0], np.zeros(len(uv)), uv[:, 1]])
        x = drape_static(
            model,
            x0,
            PlaneSDF(point=(0.0, -10.0, 0.0)),
            Cloth(torch.as_tensor(uv), stiff.gamma(), stiff.density),
        )
        tip = uv[:, 0] >= L - 1e-12
        drop = -float(x[torch.as_tensor(tip), 1].mean())
        # the hinge chain: hinge i at x_i turns by M_i h / (D W), M_i the moment of the lumped
        # masses beyond it
        xs = np.arange(nx + 1) * h
        m = np.full(nx + 1, h)
        m[-1] = h / 2
        m[0] = 0.0
        turn = np.array([(m[i + 1 :] * (xs[i + 1 :] - xs[i])).sum() for i in range(nx)]) * h
        turn[0] *= 0.5  # the hinge on the clamp's edge bends over half a cell (bending.py, "Clamped edges")
        chain = float((np.cumsum(turn) * h).sum()) * stiff.density * G / stiff.bend
        th, _ = dihedral_angle(x, model.hinges)
        e = (x[model.hinges[:, 1]] - x[model.hinges[:, 0]]).numpy()
        across = torch.as_tensor(np.abs(e[:, 0]) < 1e-6 * h)
        rows.append(
            {
                "cells": f"{nx} x {ny}",
                "cell aspect (along/across)": h / (W / ny),
                "tip drop / beam": drop / beam,
                "hinge chain / beam": chain / beam,
                "largest other hinge / largest cross hinge": float(
                    th[~across].abs().max() / th[across].abs().max()
                ),
            }
        )
    return rows


def cylinder_energy_rows(edges=(0.005, 0.01, 0.02), angles=(0, 15, 30, 45, 60, 90), *, size=0.2, radius=0.2):
    """Energy of a uniform bend: a size x size [m] sheet laid exactly on a cylinder of ``radius``
    [m] whose axis makes each angle [deg] with the mesh's x axis, the hinge energy of its interior
    (hinges 2 cm or more from the border) over plate theory's D/2 kappa^2 per unit area (each
    hinge standing for a third of its two triangles). Meshes: the grid (alternating diagonals)
    and unsew's own panel mesher (``triangulate_polygon``, 20 deg quality) at each edge [m], with
    Bridson's coefficient (the simulator's default) and calibrated (``bending_rest(calibrate=True)``)."""
    import torch

    from unsew.meshing.triangulate import triangulate_polygon
    from unsew.sim import SimModel
    from unsew.sim.energies.bending import bending_rest, dihedral_angle
    from unsew.sim.energies.membrane import membrane_rest
    from unsew.sim.meshes import grid_sheet

    corners = np.array([[0.0, 0.0], [size, 0.0], [size, size], [0.0, size], [0.0, 0.0]])
    rows = []
    for kind in ("grid", "unsew mesher"):
        for edge, cal in ((e, c) for e in edges for c in (False, True)):
            n = round(size / edge)
            if kind == "grid":
                uv, f = grid_sheet(n, n, size, size)
            else:  # the outline sampled at the edge length, as unsew samples a panel's
                t = np.linspace(0.0, 1.0, n + 1)[:-1, None]
                outline = np.concatenate([a + t * (b - a) for a, b in zip(corners[:-1], corners[1:])])
                uv, f = triangulate_polygon(outline, edge_length=edge)
            m = SimModel.build(f, f)
            uvt = torch.as_tensor(uv)
            area = membrane_rest(uvt, m.faces_uv)[0]
            coef = bending_rest(uvt, m.faces_uv, m.hinge_faces, m.hinge_uv_edges, area, calibrate=cal)
            hf = m.hinge_faces.numpy()
            mid = uv[f].mean(1)[hf].mean(1)
            inner = torch.as_tensor(np.all((mid > 0.02) & (mid < size - 0.02), 1))
            share = ((area[hf[:, 0]] + area[hf[:, 1]]) / 3.0)[inner].sum()
            row = {"mesh": f"{kind} {edge * 1000:.0f} mm", "vertices": len(uv)}
            row["coefficient"] = "calibrated" if cal else "Bridson"
            for a in angles:
                d = np.array([math.cos(math.radians(a)), math.sin(math.radians(a))])
                s, t = uv @ d, uv @ np.array([-d[1], d[0]])
                x = torch.as_tensor(np.c_[radius * np.sin(s / radius), radius * (1 - np.cos(s / radius)), t])
                th = dihedral_angle(x, m.hinges)[0]
                row[f"{a} deg"] = float((0.5 * coef * th**2)[inner].sum() / (0.5 / radius**2 * share))
            rows.append(row)
    return rows


#: newton's Style3D bending stiffness (edge_aniso_ke) of the foreign benchmark's targets
#: (benchmarks/foreign/newton_drape.py SETTINGS), per edge: ke = k0 sin^12 a + k1 cos^12 a +
#: k2 4 sin^2 a cos^2 a, a the edge's angle with the pattern's x axis
STYLE3D_KE = (2.0e-5, 1.0e-5, 5.0e-6)


def style3d_bending_energy(uv: np.ndarray, f: np.ndarray, x: np.ndarray, ke=STYLE3D_KE, *, inner=None):
    """Energy [J] of newton's Style3D bending (Bergou et al. 2006, "A quadratic bending model
    for inextensible surfaces", as newton 1.8's ``eval_bend_kernel`` writes it) of the sheet with
    rest uv (V, 2) [m], faces f (F, 3), placed at x (V, 3) [m]: per interior edge, with rest
    cotangents c1..c4 and A0 + A1 the two rest areas, 1/2 ke 3/(A0+A1) |w . (x_o0, x_o1, x_e0,
    x_e1)|^2, w = (-(c1+c3), -(c2+c4), c3+c4, c1+c2); ke: (k0, k1, k2) [N*m] by the edge's
    direction (:data:`STYLE3D_KE`) or one value for every edge. ``inner``: (E,) bool over the edges of
    :func:`_interior_edges` to sum, or None (all). Returns (energy [J], the summed (A0+A1)/3 [m^2])."""
    e, o = _interior_edges(f)
    p0, p1, q0, q1 = uv[e[:, 0]], uv[e[:, 1]], uv[o[:, 0]], uv[o[:, 1]]

    def cot(a, b, c):  # cotangent of the angle at a in the triangle (a, b, c)
        u, v = b - a, c - a
        return (u * v).sum(1) / np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])

    c1, c2, c3, c4 = cot(p0, p1, q0), cot(p0, p1, q1), cot(p1, p0, q0), cot(p1, p0, q1)
    w = np.stack([-(c1 + c3), -(c2 + c4), c3 + c4, c1 + c2], 1)  # (E, 4)
    cross = lambda a, b: np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])  # noqa: E731
    area2 = 0.5 * (cross(p1 - p0, q0 - p0) + cross(p1 - p0, q1 - p0))  # A0 + A1 [m^2]
    d = p1 - p0
    ang = np.arctan2(d[:, 1], d[:, 0])
    s2, c2a = np.sin(ang) ** 2, np.cos(ang) ** 2
    if np.ndim(ke) == 0:  # one ke for every edge
        k = np.full(len(e), float(ke))
    else:
        k = ke[0] * s2**6 + ke[1] * c2a**6 + ke[2] * 4.0 * s2 * c2a
    vec = np.einsum("ek,ekc->ec", w, np.stack([x[o[:, 0]], x[o[:, 1]], x[e[:, 0]], x[e[:, 1]]], 1))
    en = 0.5 * k * 3.0 / area2 * (vec * vec).sum(1)
    sel = np.ones(len(e), bool) if inner is None else inner
    return float(en[sel].sum()), float((area2 / 3.0)[sel].sum())


def _interior_edges(f: np.ndarray):
    """Interior edges of faces f (F, 3): (E, 2) vertex pairs and (E, 2) the opposite vertices."""
    ed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    opp = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    key = np.sort(ed, 1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, opp, ed = key[order], opp[order], ed[order]
    same = np.all(key[1:] == key[:-1], 1)
    i = np.nonzero(same)[0]
    return key[i], np.stack([opp[i], opp[i + 1]], 1)


def style3d_bending_rows(edges=(0.01, 0.025), angles=(0, 45, 90), *, size=0.3, radius=0.2, ke=STYLE3D_KE):
    """The plate rigidity D_eq [N*m] newton's Style3D bending (``ke``, or one ke [N*m] for every
    edge) stands for. A size x size [m] sheet meshed by unsew's panel mesher at each edge [m] is
    laid on a cylinder of ``radius`` [m] whose axis makes each angle with the pattern's x axis
    (0 deg: the sheet curves along y, the weft); D_eq = 2 E / (kappa^2 A) over the edges 2 cm or
    more from the border. A ke of 1 for every edge gives the factor alone. The newton targets'
    fabric is compared with unsew's by D_eq and the bending length (D_eq / (w g))^(1/3)."""
    from unsew.meshing.triangulate import triangulate_polygon

    corners = np.array([[0.0, 0.0], [size, 0.0], [size, size], [0.0, size], [0.0, 0.0]])
    rows = []
    for edge in edges:
        n = round(size / edge)
        t = np.linspace(0.0, 1.0, n + 1)[:-1, None]
        outline = np.concatenate([a + t * (b - a) for a, b in zip(corners[:-1], corners[1:])])
        uv, f = triangulate_polygon(outline, edge_length=edge)
        e, o = _interior_edges(np.asarray(f))
        mid = 0.25 * (uv[e[:, 0]] + uv[e[:, 1]] + uv[o[:, 0]] + uv[o[:, 1]])
        inner = np.all((mid > 0.02) & (mid < size - 0.02), 1)
        for name, k in (("one ke for all edges (D_eq / ke)", 1.0), ("newton targets' ke (D_eq, uN m)", ke)):
            row = {"mesh": f"unsew mesher {edge * 1000:.0f} mm", "ke": name}
            for a in angles:
                d = np.array([math.cos(math.radians(a)), math.sin(math.radians(a))])
                s, tt = uv @ np.array([-d[1], d[0]]), uv @ d  # s runs across the axis
                x = np.c_[radius * np.sin(s / radius), radius * (1 - np.cos(s / radius)), tt]
                en, share = style3d_bending_energy(uv, np.asarray(f), x, k, inner=inner)
                one = np.ndim(k) == 0
                d_eq = 2 * en * radius**2 / share  # E = D_eq / 2 kappa^2 A
                row[f"axis {a} deg"] = d_eq if one else 1e6 * d_eq
            rows.append(row)
    return rows


# -- the simulated Cusick drape --------------------------------------------------------------


def specimen_mesh(radius: float, disc: float, edge: float):
    """A disc of ``radius`` [m] meshed by triangle with a circle of the support's radius ``disc``
    [m] among its edges; target edge length ``edge`` [m]. Returns uv (V, 2), faces (F, 3)."""
    import triangle

    def ring(r):
        n = max(12, round(2 * math.pi * r / edge))
        a = 2 * math.pi * np.arange(n) / n
        return np.c_[r * np.cos(a), r * np.sin(a)]

    outer, inner = ring(radius), ring(disc)
    no, ni = len(outer), len(inner)
    verts = np.concatenate([outer, inner])
    segs = np.concatenate(
        [np.c_[np.arange(no), (np.arange(no) + 1) % no], no + np.c_[np.arange(ni), (np.arange(ni) + 1) % ni]]
    )
    amax = math.sqrt(3) / 4 * edge * edge
    t = triangle.triangulate({"vertices": verts, "segments": segs}, f"pq30a{amax:.12f}")
    return np.asarray(t["vertices"], float), np.asarray(t["triangles"], np.int64)


def shadow_area(x: np.ndarray, faces: np.ndarray, *, pixel: float = 5e-4) -> float:
    """Area [m^2] of the vertical (-Y) projection of a triangle mesh x (V, 3), rasterized on a
    grid of ``pixel`` [m] (each pixel centre inside any projected triangle counts)."""
    p = x[:, [0, 2]]
    lo = p.min(0) - pixel
    n = np.ceil((p.max(0) + pixel - lo) / pixel).astype(int)
    hit = np.zeros((n[0], n[1]), bool)
    for a, b, c in p[faces]:
        i0, j0 = np.floor((np.minimum(np.minimum(a, b), c) - lo) / pixel).astype(int)
        i1, j1 = np.ceil((np.maximum(np.maximum(a, b), c) - lo) / pixel).astype(int)
        gi, gj = np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1), indexing="ij")
        q = lo + (np.stack([gi, gj], -1) + 0.5) * pixel
        d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if abs(d) < 1e-18:
            continue
        l1 = ((b[0] - q[..., 0]) * (c[1] - q[..., 1]) - (b[1] - q[..., 1]) * (c[0] - q[..., 0])) / d
        l2 = ((c[0] - q[..., 0]) * (a[1] - q[..., 1]) - (c[1] - q[..., 1]) * (a[0] - q[..., 0])) / d
        inside = (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
        ii, jj = gi[inside], gj[inside]
        ok = (ii < n[0]) & (jj < n[1])
        hit[ii[ok], jj[ok]] = True
    return float(hit.sum()) * pixel * pixel


def hem_profile(x: np.ndarray, hem: np.ndarray, *, bins: int = 720):
    """The hem's projected outline radius [m] per angle bin (bins,), the hem polyline resampled
    densely; bins no hem point falls in are filled by periodic interpolation."""
    p = x[hem][:, [0, 2]]
    q = np.concatenate([p, p[:1]])
    dense = np.concatenate([np.linspace(q[i], q[i + 1], 8, endpoint=False) for i in range(len(p))])
    ang = np.mod(np.arctan2(dense[:, 1], dense[:, 0]), 2 * math.pi)
    r = np.hypot(dense[:, 0], dense[:, 1])
    k = np.minimum((ang / (2 * math.pi) * bins).astype(int), bins - 1)
    prof = np.full(bins, np.nan)
    np.fmax.at(prof, k, r)
    good = ~np.isnan(prof)
    idx = np.arange(bins)
    prof[~good] = np.interp(idx[~good], idx[good], prof[good], period=bins)
    return prof


def count_nodes(profile: np.ndarray, *, prominence: float) -> int:
    """Number of folds: local maxima of the periodic outline radius (m) standing at least
    ``prominence`` [m] above the deeper of the two troughs beside them."""
    from scipy.signal import find_peaks

    n = len(profile)
    ext = np.concatenate([profile, profile, profile])
    peaks, _ = find_peaks(ext, prominence=prominence)
    return int(((peaks >= n) & (peaks < 2 * n)).sum())


@dataclass
class DrapeResult:
    """One simulated Cusick test: DC [-], node count, outline profile (bins,) [m], positions
    x (V, 3) [m], faces (F, 3), hem indices, wall time [s], Newton iterations."""

    dc: float
    nodes: int
    profile: np.ndarray
    x: np.ndarray
    faces: np.ndarray
    hem: np.ndarray
    wall_s: float
    iterations: int


def simulate_drape(
    fab: Fabric,
    *,
    edge: float,
    seed: int = 0,
    radius: float = 0.15,
    disc: float = 0.09,
    lift: float = 2e-3,
    max_iter: int = 2000,
) -> DrapeResult:
    """The Cusick test of ``fab``: specimen of ``radius`` [m] clamped on a support of radius
    ``disc`` [m], meshed at ``edge`` [m]; the free vertices start lifted by a seeded random
    height in [0, lift] [m] times their distance from the support over the overhang; at most
    ``max_iter`` Newton iterations (the light fabrics on fine meshes take several hundred)."""
    import torch

    from unsew.sim import Cloth, PlaneSDF, SimModel, StaticInfo, StaticSettings, drape_static

    t = time.perf_counter()
    uv, f = specimen_mesh(radius, disc, edge)
    r = np.hypot(uv[:, 0], uv[:, 1])
    pinned = r <= disc + 1e-9
    hem = np.nonzero(r >= radius - 1e-9)[0]
    hem = hem[np.argsort(np.arctan2(uv[hem, 1], uv[hem, 0]))]
    model = SimModel.build(f, f, pinned=pinned)
    rng = np.random.default_rng(seed)
    y0 = np.where(pinned, 0.0, rng.uniform(0.0, lift, len(uv)) * (r - disc) / (radius - disc))
    x0 = torch.as_tensor(np.c_[uv[:, 0], y0, uv[:, 1]])
    info = StaticInfo()
    far = PlaneSDF(point=(0.0, -10.0, 0.0))
    x = drape_static(
        model,
        x0,
        far,
        Cloth(torch.as_tensor(uv), fab.gamma(), fab.density),
        settings=StaticSettings(max_iter=max_iter),
        info=info,
    ).numpy()
    a_disc, a_spec = math.pi * disc**2, math.pi * radius**2
    dc = (shadow_area(x, f) - a_disc) / (a_spec - a_disc)
    prof = hem_profile(x, hem)
    nodes = count_nodes(prof, prominence=max(2e-3, 0.05 * (prof.max() - prof.min())))
    return DrapeResult(dc, nodes, prof, x, f, hem, time.perf_counter() - t, info.iterations)


def drape_rows(cases, *, log=print):
    """One row per case (fabric, edge [m], seeds): DC per seed (mean and range) and nodes, with
    the bending length."""
    rows, results = [], {}
    for fab, edge, seeds in cases:
        runs = []
        for seed in seeds:
            r = simulate_drape(fab, edge=edge, seed=seed)
            runs.append(r)
            log(
                f"  drape {fab.name} seed {seed}: DC {100 * r.dc:.1f} %, {r.nodes} nodes "
                f"({len(r.x)} vertices, {r.iterations} Newton iterations, {r.wall_s:.1f} s)"
            )
        results.setdefault(fab.name, runs)
        dcs = [100 * r.dc for r in runs]
        rows.append(
            {
                "fabric": fab.name,
                "D uN m": fab.bend * 1e6,
                "w g/m2": fab.density * 1000,
                "c cm": fab.bending_length * 100,
                "H22 N/m": fab.membrane[3],
                "mesh": f"{edge * 1000:.0f} mm, {len(runs[0].x)} vertices",
                "DC %": float(np.mean(dcs)),
                "DC range %": f"{min(dcs):.1f}-{max(dcs):.1f}",
                "nodes": "/".join(str(r.nodes) for r in runs),
                "DC % measured": fab.dc_measured,
                "DC % CLO3D": fab.dc_other_sim,
            }
        )
    return rows, results


# -- figures ---------------------------------------------------------------------------------


def drape_figure(
    results: dict, path: Path, *, disc: float = 0.09, radius: float = 0.15, measured: dict | None = None
) -> None:
    """The first seed's draped specimen of each fabric seen from above: the shadow (projected
    triangles), the support disc and the flat specimen's outline; DC and nodes in the title, and
    the measured DC [%] where ``measured`` (name -> DC) gives one."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    names = list(results)
    n = len(names)
    cols = min(n, 4)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(2.4 * cols, 2.5 * rows), squeeze=False)
    t = np.linspace(0, 2 * math.pi, 200)
    for ax, name in zip(axes.flat, names):
        r = results[name][0]
        p = r.x[:, [0, 2]] * 100
        depth = r.x[:, 1] * 100
        polys = p[r.faces]
        shade = depth[r.faces].mean(1)
        pc = PolyCollection(polys, array=shade, cmap="Blues_r", edgecolors="none", clim=(-6.0, 0.0))
        ax.add_collection(pc)
        ax.plot(radius * 100 * np.cos(t), radius * 100 * np.sin(t), "k--", lw=0.6)
        ax.fill(disc * 100 * np.cos(t), disc * 100 * np.sin(t), color="0.55", alpha=0.8)
        hem = np.concatenate([r.hem, r.hem[:1]])
        ax.plot(p[hem, 0], p[hem, 1], "r-", lw=0.6)
        ax.set_aspect("equal")
        ax.set_xlim(-16, 16)
        ax.set_ylim(-16, 16)
        ax.set_xticks([])
        ax.set_yticks([])
        real = (measured or {}).get(name)
        label = f"DC {100 * r.dc:.0f} %, {r.nodes} nodes" + (f"\nmeasured DC {real:.0f} %" if real else "")
        ax.set_title(f"{name}\n{label}", fontsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle(f"Cusick drape, {200 * radius:.0f} cm on {200 * disc:.0f} cm, from above", fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=72)
    plt.close(fig)


def cantilever_figure(shapes: dict, fabrics, path: Path, *, kind: str = "tri") -> None:
    """Each fabric's simulated strip (centre-line profile, side view) at the overhang where its
    chord meets the 41.5 deg incline, with the exact elastica of the same D and w."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.0, 3.4))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    lam = elastica_overhang()
    lmax = 0.0
    for i, fab in enumerate(fabrics):
        col = colors[i % len(colors)]
        for (name, k), (uv, x, l_sim) in shapes.items():
            if name != fab.name or k != kind:
                continue
            # the vertices nearest the strip's middle line (a row of a grid, a band of a tri mesh)
            mid = (
                np.abs(uv[:, 1] - 0.5 * uv[:, 1].max())
                <= np.abs(uv[:, 1] - 0.5 * uv[:, 1].max()).min() + 2e-3
            )
            order = np.argsort(uv[mid, 0])
            px, py = x[mid][order, 0] * 100, x[mid][order, 1] * 100
            keep = px >= -1e-9
            ax.plot(px[keep], py[keep], "-o", color=col, ms=2, lw=1, label=f"{fab.name} (sim)")
            lmax = max(lmax, l_sim * 100)
        ex, ey = elastica(lam)
        c = fab.bending_length * 100
        ax.plot(ex * c, -ey * c, ":", color=col, lw=1)
    s = np.linspace(0, lmax * 1.1, 10)
    ax.plot(s, -np.tan(PEIRCE_ANGLE) * s, "k-", lw=1.2, label="41.5 deg incline")
    ax.axhline(0, color="0.5", lw=0.5)
    ax.fill_between([-1.0, 0.0], [-0.3, -0.3], [0.0, 0.0], color="0.6")
    ax.set_aspect("equal")
    ax.set_xlabel("x [cm] (platform edge at 0)")
    ax.set_ylabel("y [cm]")
    ax.set_title(
        "Cantilever: strips at the overhang their tip meets 41.5 deg\n(dotted: exact elastica)", fontsize=8
    )
    ax.legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


# -- entry -----------------------------------------------------------------------------------


def _print_table(title: str, rows: list[dict]) -> None:
    from tables import markdown_table

    print(f"\n{title}\n")
    print(markdown_table(rows, digits=2))


def _record(tables: dict, args) -> None:
    """Write each table into benchmarks/results/fabric_<name>.json with its command and commit."""
    flags = " --small" if args.small else " --linear" if args.linear else ""
    flags += " --skip-drape" * (args.skip_drape and not args.linear)
    flags += " --skip-cantilever" * (args.skip_cantilever and not args.linear)
    cmd = "python -m benchmarks fabric_tests" + flags + " --record"
    titles = {
        "bend_energy": "Uniform bend: hinge energy of a sheet on a cylinder over plate theory, by axis angle",
        "style3d_bend": "newton's Style3D bending (Bergou 2006) on a cylinder: plate rigidity D_eq",
        "strip_linear": "Small-deflection strip on unsew's hinges: tip drop against the beam formula",
        "cantilever": "Cantilever test (Peirce, 41.5 deg) on unsew's strip: overhang, rigidity read",
        "drape": "Cusick drape test (30 cm specimen, 18 cm support) simulated: DC and nodes",
    }
    RESULTS.mkdir(exist_ok=True)
    from tables import git_commit

    for key, rows in tables.items():
        rec = {"title": titles[key], "command": cmd, "commit": git_commit(), "rows": rows}
        (RESULTS / f"fabric_{key}.json").write_text(json.dumps(rec, indent=1) + "\n")


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--small", action="store_true", help="one fabric, coarse meshes, one seed (seconds)")
    ap.add_argument("--seeds", type=int, default=2, help="drape starts per fabric (default 2)")
    ap.add_argument("--drape-edge", type=float, default=0.015, help="specimen mesh edge [m] (default 0.015)")
    ap.add_argument(
        "--published-edge",
        type=float,
        default=0.005,
        help="specimen mesh edge [m] for the fabrics with a published DC (default 0.005; their bending "
        "lengths are about 1 cm)",
    )
    ap.add_argument("--strip-edge", type=float, default=0.005, help="strip mesh edge [m] (default 0.005)")
    ap.add_argument("--figures", type=Path, default=None, help="write the two PNGs into this folder")
    ap.add_argument("--record", action="store_true", help="write benchmarks/results/fabric_*.json")
    ap.add_argument("--skip-drape", action="store_true")
    ap.add_argument(
        "--only",
        nargs="+",
        default=None,
        metavar="NAME",
        help="only the fabrics whose name contains one of these (no mesh or shear studies; the drape "
        "figure goes to fabric_drape_selected.png; not with --record)",
    )
    ap.add_argument("--skip-cantilever", action="store_true")
    ap.add_argument(
        "--linear", action="store_true", help="only the small-deflection strip on grids of several cells"
    )
    return ap.parse_args(argv)


def _cantilever_table(fabrics, cotton, args, studies: bool) -> list[dict]:
    """The cantilever rows: every fabric on an unstructured strip (the kind of mesh unsew's panels
    get), and with ``studies`` cotton on both kinds at half and twice the edge; the figure."""
    kind, e = "tri", args.strip_edge
    cases = [(f, kind, e) for f in fabrics]
    if studies:  # the mesh's share: coarser and finer strips of both kinds
        cases += [(cotton, k, s * e) for k in ("grid", "tri") for s in (2, 0.5)] + [(cotton, "grid", e)]
    rows, shapes = cantilever_rows(cases)
    _print_table("Cantilever (41.5 deg): the rigidity the instrument reads from the simulated strip", rows)
    if args.figures:
        shown = [cotton] + [f for f in fabrics if f.name in ("unsew silk", "unsew denim")]
        cantilever_figure(shapes, shown, args.figures / "fabric_cantilever.png", kind=kind)
    return rows


def _drape_studies(cotton: Fabric, e: float, seeds) -> list:
    """The drape's studies: cotton's mesh (twice and two thirds the edge ``e`` [m]) and shear
    (H22 x0.1, x10); the published fabrics of Petrak et al. 2025 on coarser meshes (``e``, 10 and
    7.5 mm) and, on the 7.5 mm mesh, with unsew's cotton membrane in place of their own."""
    cases = [(cotton, 2 * e, seeds), (cotton, 2 * e / 3, range(1))]
    for k in (0.1, 10.0):
        h = cotton.membrane
        soft = dataclasses.replace(
            cotton, name=f"unsew cotton, shear x{k:g}", membrane=(h[0], h[1], h[2], k * h[3])
        )
        cases.append((soft, e, seeds))
    cases += [(f, edge, seeds) for edge in (e, 0.01, 0.0075) for f in petrak_fabrics()]
    return cases + [(f, 0.0075, seeds) for f in petrak_fabrics(membrane="cotton")]


def _drape_figures(results: dict, fabrics, args) -> None:
    """fabric_drape.png: the library's, Wang's and the newton targets' fabrics;
    fabric_drape_published.png: the fabrics with a published DC, measured DC in the titles
    (with --only: every fabric run, in fabric_drape_selected.png)."""
    measured = {f.name: f.dc_measured for f in fabrics if f.dc_measured is not None}
    if args.only:
        drape_figure(results, args.figures / "fabric_drape_selected.png", measured=measured)
        return
    plain = {k: v for k, v in results.items() if "shear" not in k and "membrane" not in k}
    drape_figure({k: v for k, v in plain.items() if k not in measured}, args.figures / "fabric_drape.png")
    published = {k: v for k, v in plain.items() if k in measured}
    if published:
        drape_figure(published, args.figures / "fabric_drape_published.png", measured=measured)


def main(argv=None) -> int:
    args = _parse(argv)

    import torch

    torch.set_num_threads(1)
    fabrics = library_fabrics() + wang_fabrics() + [newton_target_fabric()] + petrak_fabrics()
    cotton = next(f for f in fabrics if f.name == "unsew cotton")
    studies = not (args.small or args.only)
    if args.small:
        fabrics = [cotton]
        args.seeds, args.drape_edge, args.strip_edge = 1, 0.03, 0.01
    if args.only:
        fabrics = [f for f in fabrics if any(k in f.name for k in args.only)]
        if not fabrics or args.record:
            print("fabric_tests: --only matched no fabric, or came with --record", file=sys.stderr)
            return 2
    lam = elastica_overhang()
    print(
        f"elastica: chord at 41.5 deg when overhang / c = {lam:.4f} (Peirce's formula: "
        f"{1 / peirce_ratio():.4f}; the instrument reads c = overhang / 2)"
    )
    tables = {}
    rows = cylinder_energy_rows(edges=(0.01,) if args.small else (0.005, 0.01, 0.02))
    _print_table("Uniform bend: hinge energy of a sheet laid on a cylinder / D/2 kappa^2 area", rows)
    tables["bend_energy"] = rows
    rows = style3d_bending_rows(edges=(0.025,) if args.small else (0.01, 0.025))
    _print_table("newton's Style3D bending on a cylinder: the plate rigidity D_eq it stands for", rows)
    tables["style3d_bend"] = rows
    if args.linear:
        rows = linear_strip_rows(cotton)
        _print_table("Small-deflection strip (cotton's weight, 1000 x its D): tip drop / beam formula", rows)
        tables["strip_linear"] = rows
        args.skip_cantilever = args.skip_drape = True
    if not args.skip_cantilever:
        tables["cantilever"] = _cantilever_table(fabrics, cotton, args, studies)
    if not args.skip_drape:
        seeds = range(args.seeds)
        cases = [(f, args.published_edge if f.dc_measured else args.drape_edge, seeds) for f in fabrics]
        if studies:
            cases += _drape_studies(cotton, args.drape_edge, seeds)
        rows, results = drape_rows(cases)
        _print_table("Cusick drape (30 cm on 18 cm): drape coefficient and nodes", rows)
        tables["drape"] = rows
        if args.figures:
            _drape_figures(results, fabrics, args)
    if args.record:
        _record(tables, args)
    return 0


if __name__ == "__main__":
    if "--flared-floor" in sys.argv[1:]:  # the flared skirts' floors: _flared_floor.py
        from _flared_floor import main as flared_floor

        sys.exit(flared_floor([a for a in sys.argv[1:] if a != "--flared-floor"]))
    if "--newton-cantilever" in sys.argv[1:]:  # newton's settling: _newton_cantilever.py
        from _newton_cantilever import main as newton_cantilever

        sys.exit(newton_cantilever([a for a in sys.argv[1:] if a != "--newton-cantilever"]))
    sys.exit(main())
