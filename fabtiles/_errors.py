"""The exception tree of fabtiles.

Every error fabtiles raises on purpose is a :class:`FabtilesError`. The leaves
for bad input are also :class:`ValueError`, so code written against plain
Python conventions catches them too. The CLI turns a ``FabtilesError`` into one
line on stderr and exit status 2; anything else escaping is a bug.
"""

from __future__ import annotations


class FabtilesError(Exception):
    """Root of every error fabtiles raises on purpose."""


class ParameterError(FabtilesError, ValueError):
    """A parameter is out of its allowed range or of the wrong kind."""


class ProfileError(FabtilesError, ValueError):
    """A machine/material profile is missing, unreadable or invalid."""


class DesignError(FabtilesError, ValueError):
    """A design file is unreadable or holds an unknown or bad key."""


class FabricationError(FabtilesError, ValueError):
    """The part cannot be made as asked (strict fabrication checks, bad mesh)."""


class LimitError(FabtilesError, ValueError):
    """The job is larger than a set work limit; it is refused before work starts."""
