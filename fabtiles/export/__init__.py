"""The writers, one module per format, each importing its heavy library only when used.

:mod:`~fabtiles.export.dispatch` picks the writer for a file's suffix (the one place
that does): ``.dxf`` :mod:`~fabtiles.export.dxf`, ``.svg``
:mod:`~fabtiles.export.laser_svg`, ``.stl`` :mod:`~fabtiles.export.stl`, ``.3mf``
:mod:`~fabtiles.export.threemf`, ``.step`` :mod:`~fabtiles.export.step` (its text
:mod:`~fabtiles.export.step_file`). Pictures: :mod:`~fabtiles.export.motif_svg` (one
motif), :mod:`~fabtiles.export.preview_svg` (a tile, its findings marked);
:mod:`~fabtiles.export.card` writes the laser calibration card. The bodies they write
are built and checked in :mod:`fabtiles.solid`.
"""
