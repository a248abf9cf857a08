"""Losses the optimizer minimizes (paper 3.5, eqs. 5-9): torch, float64, differentiable.

Import from the modules: :mod:`unsew.losses.chamfer` (``loss_chamfer``),
:mod:`unsew.losses.curvature` (``curvature_weights``, ``mean_curvature``),
:mod:`unsew.losses.contours` (``open_contours``, ``loss_open_contours``),
:mod:`unsew.losses.seam` (``loss_seam``), :mod:`unsew.losses.material` (``loss_material``),
:mod:`unsew.losses.nn` (``nearest_indices``), :mod:`unsew.losses.prior` (``loss_prior``). This package imports
nothing heavy.
"""
