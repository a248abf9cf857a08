"""body stage of unsew (see docs/ARCHITECTURE.md): the wearer's mesh, skeleton (given or rigged
from the mesh), measurements, signed distance, the placement of a pattern's panels around it, and
the loading of a whole case with its wearer.

Public names load lazily (``from unsew.body import default_body`` imports only what it needs).
"""

from __future__ import annotations

import importlib

__all__ = [
    "Body",
    "default_body",
    "load_body",
    "Skeleton",
    "Bone",
    "load_skeleton",
    "save_skeleton",
    "axial_coordinate",
    "distance_to_bone",
    "encircled_bones",
    "Measurements",
    "measure_body",
    "BodySDF",
    "place_garment",
    "rig_skeleton",
    "render_rig_preview",
    "load_case",
]

_WHERE = {
    "Body": "body",
    "default_body": "body",
    "load_body": "body",
    "Skeleton": "skeleton",
    "Bone": "skeleton",
    "load_skeleton": "skeleton",
    "save_skeleton": "skeleton",
    "axial_coordinate": "skeleton",
    "distance_to_bone": "skeleton",
    "encircled_bones": "skeleton",
    "Measurements": "measurements",
    "measure_body": "measure",
    "BodySDF": "sdf",
    "place_garment": "placement",
    "rig_skeleton": "rig",
    "render_rig_preview": "preview",
    "load_case": "case",
}


def __getattr__(name: str):
    if name in _WHERE:
        return getattr(importlib.import_module(f"unsew.body.{_WHERE[name]}"), name)
    raise AttributeError(f"module 'unsew.body' has no attribute {name!r}")
