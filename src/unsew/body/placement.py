"""Placement of a pattern's panels around a body (issue 3, item 6).

OWNERSHIP NOTE (lead, during parallel work): this module is being written by the *dressing*
engineer together with the sewing phase and `unsew.dress`. The body engineer need not write it.
Contract (docs/ARCHITECTURE.md): ``place_garment(pattern, mesh, body) -> x_unsewn (Nu, 3) [m]``.
"""
