"""Shapely layer: stroking, union, clipping, validation."""
