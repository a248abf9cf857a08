"""The geometry core: point-to-mesh queries on libigl's AABB tree (:mod:`unsew.geometry.distance`),
mesh connectivity (:mod:`unsew.geometry.topology`) and the repair of damaged meshes on load
(:mod:`unsew.geometry.repair`). Import from the modules; this package imports nothing heavy.
"""
