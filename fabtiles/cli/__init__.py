"""The ``fabtiles`` command line. Heavy libraries are imported inside commands only."""
