"""The printed bodies: which area stands at which height, the meshes, their check, the B-rep.

- :mod:`~fabtiles.solid.levels`: the levels of a printed body (relief, pierced,
  deboss; an interlaced relief's dips), as polygons at heights;
- :mod:`~fabtiles.solid._mesh_build` and :mod:`~fabtiles.solid._triangulate`: stacked
  prisms over a planar coverage of those levels, and their triangulation;
- :mod:`~fabtiles.solid.mesh_check`: the mesh checked as a slicer reads it (float32
  corners merged by position: watertight, consistently wound, of the volume and body
  count expected);
- :mod:`~fabtiles.solid.parts`: the checked parts of a print by name (the 3MF's base
  and pattern, the STL's one fused body);
- :mod:`~fabtiles.solid.brep`: the planar boundary representation a STEP file holds;
- :mod:`~fabtiles.solid.cylinder`: a flat print of the unrolled strip wrapped onto a
  cylinder (texture rollers, lampshades with a lamp holder), read by the mesh writers
  as a print model is.
- :mod:`~fabtiles.solid.stamp`: a clay stamp, a relief on a block with a finger grip that
  prints without supports.

Nothing here writes a file: the formats are :mod:`fabtiles.export`'s (a contract in
``.importlinter``).
"""
