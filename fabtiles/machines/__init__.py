"""The machines: cutter and printer profiles, the kinds of cutter, and the work limits.

Above the core; the pattern, geometry and every later layer may read it.
"""
