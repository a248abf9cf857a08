"""unsew: inverse garment and pattern modeling with a differentiable cloth simulator.

Turns a 3D garment mesh into the 2D sewing pattern that makes it (panels, curves, control
points, seams), the fabric's stiffness, and a simulation-ready garment, following
Yu, Cordier and Seo, "Inverse Garment and Pattern Modeling with a Differentiable Simulator".

``import unsew`` is cheap: heavy dependencies (torch, scipy, trimesh) are imported by the
submodules that need them.
"""

__all__ = ["__version__", "UnsewError"]

__version__ = "0.1.0"

from unsew.errors import UnsewError  # noqa: E402
