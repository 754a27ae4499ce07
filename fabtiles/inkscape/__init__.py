"""The Inkscape extension's files (``fabtiles_render.inx`` and its script), copied into Inkscape's
extensions folder by ``fabtiles install-inkscape-extension`` (:mod:`fabtiles.cli.inkscape`)."""
