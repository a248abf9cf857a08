"""report stage of unsew (see docs/ARCHITECTURE.md): pictures and the HTML report of a fit.

- :mod:`unsew.report.render`: ``render_mesh``, ``render_views``, ``render_comparison`` (garment
  meshes to PNG, orthographic, matplotlib only).
- :mod:`unsew.report.figures`: ``plot_loss_curves``, ``plot_patterns``, ``pattern_outlines``,
  ``plot_histogram``.
- :mod:`unsew.report.html`: ``write_report`` (one self-contained HTML file).
- :mod:`unsew.report.fit_report`: ``write_fit_report`` (every figure of a fit and report.html
  in one call, for the fit loop).

Importing this package is cheap; matplotlib is imported by the functions that draw.
"""

__all__: list[str] = []
