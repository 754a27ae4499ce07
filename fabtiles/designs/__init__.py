"""The design: a design file read and checked into frozen dataclasses, and its colours.

Above the writers and below the build (``fabtiles.making``), which turns a design into files.
"""
