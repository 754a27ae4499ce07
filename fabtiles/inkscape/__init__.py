"""The Inkscape extension's files (``fabtiles_render.inx`` and its script, kept as the template
``fabtiles_render.py.in``), copied into Inkscape's
extensions folder by ``fabtiles install-inkscape-extension`` (:mod:`fabtiles.cli.inkscape`)."""
