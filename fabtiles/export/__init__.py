"""The writers: pure functions from a model to a file's bytes, one module per format.

:mod:`~fabtiles.export.formats` is the table of formats (the one place a format is
named): ``.dxf`` :mod:`~fabtiles.export.dxf`, ``.svg`` :mod:`~fabtiles.export.laser_svg`,
``.lbrn2`` :mod:`~fabtiles.export.lbrn2` (from a cut plan,
:mod:`fabtiles.geometry.cut_plan`); ``.stl`` :mod:`~fabtiles.export.stl`, ``.3mf``
:mod:`~fabtiles.export.threemf`, ``.step`` :mod:`~fabtiles.export.step` (its text
:mod:`~fabtiles.export.step_file`), ``.glb`` :mod:`~fabtiles.export.glb` (from a print
model, :mod:`fabtiles.solid.print_model`). Each imports its heavy library only when
used. Pictures: :mod:`~fabtiles.export.motif_svg` (one motif),
:mod:`~fabtiles.export.preview_svg` (a tile, its findings marked);
:mod:`~fabtiles.export.card` the laser calibration card; :mod:`~fabtiles.export.kit`
an inlay kit's files. The build pipeline (:mod:`fabtiles.making`) writes every file of
a model: ``Tile.export``, :func:`fabtiles.making.export_region`, ``fabtiles build``.
"""
