"""Pure math of the patterns: motifs on concentric circles and circle packings.

Only numpy here: no shapely, no file I/O.
"""
