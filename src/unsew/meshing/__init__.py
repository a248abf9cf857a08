"""meshing stage of unsew (see docs/ARCHITECTURE.md): panel triangulation and the sewn garment mesh."""

from unsew.meshing.sew import GarmentMesh, mesh_pattern, write_rest_obj

__all__ = ["GarmentMesh", "mesh_pattern", "write_rest_obj"]
