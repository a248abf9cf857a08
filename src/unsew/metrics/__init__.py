"""Evaluation metrics (paper 4.2, Tables 2 and 3): no gradients, units in the names.

Import from the modules: :mod:`unsew.metrics.surface` (``chamfer_mm``, ``normal_error``,
``surface_metrics``, ``closest_points``, ``sample_surface``), :mod:`unsew.metrics.turning`
(``turning_distance``, ``panel_turning_distance``, ``turning_function``),
:mod:`unsew.metrics.panels` (``match_panels``, ``area_error``, ``panel_area``,
``panel_vertex_l2_cm``, ``pattern_metrics``), :mod:`unsew.metrics.evaluate`
(``evaluate_result``, the work of ``unsew eval``). This package imports nothing heavy.
"""
