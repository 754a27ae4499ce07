"""The exception tree of fabtiles.

Every error fabtiles raises on purpose is a :class:`FabtilesError`. The leaves
for bad input are also :class:`ValueError`, so code written against plain
Python conventions catches them too. The CLI turns a ``FabtilesError`` into one
line on stderr and exit status 2; anything else escaping is a bug.
"""

from __future__ import annotations

from typing import Any


class FabtilesError(Exception):
    """Root of every error fabtiles raises on purpose.

    ``param`` names what the error is about, when that is one parameter: a
    keyword argument (``"stroke"``) or, for a design, its key (``"tile.stroke"``).
    Front ends use it to point at the field to fix, instead of reading the message.
    ``key`` is the most precise key the error is about (default: ``param``): a motif
    of ``[packing.motifs]`` is ``"packing.motifs.6"`` where ``param`` is ``"packing.motifs"``.

    >>> err = ParameterError("stroke must be > 0, got -1", param="stroke")
    >>> err.param, err.key, str(err)
    ('stroke', 'stroke', 'stroke must be > 0, got -1')
    >>> import pickle
    >>> pickle.loads(pickle.dumps(err)).param, pickle.loads(pickle.dumps(err)).key
    ('stroke', 'stroke')
    """

    def __init__(self, *args, param: str | None = None, key: str | None = None):
        super().__init__(*args)
        self.param = param
        self.key = key if key is not None else param

    def __reduce__(self):
        # Keep ``param`` across processes (batch and cluster workers).
        return (_rebuild, (type(self), self.args, self.param, self.__dict__))


def _rebuild(cls, args, param, state):
    err = cls.__new__(cls)
    Exception.__init__(err, *args)
    err.__dict__.update(state)
    err.param = param
    return err


class ParameterError(FabtilesError, ValueError):
    """A parameter is out of its allowed range or of the wrong kind."""


class ProfileError(FabtilesError, ValueError):
    """A machine/material profile is missing, unreadable or invalid."""


class DesignError(FabtilesError, ValueError):
    """A design file is unreadable or holds an unknown or bad key."""


class FabricationError(FabtilesError, ValueError):
    """The part cannot be made as asked (strict fabrication checks, bad mesh)."""

    mesh: tuple | None = None
    """A bad mesh's ``(vertices, faces)``, merged by float32 position, when the check has one (or None)."""
    points: Any = None
    """Where a triangulation stopped, an ``(n, 2)`` array of x, y in mm, when known (or None)."""


class LimitError(FabtilesError, ValueError):
    """The job is larger than a set work limit; it is refused before work starts."""


def did_you_mean(name, valid) -> str:
    """``"did you mean 'x'?"`` for the valid name closest to a mistyped ``name``, or ``""`` when none is close.

    Every message about an unknown name (a key, a preset, a tiling, a profile, a choice)
    asks it this way.

    >>> did_you_mean("table3-33", ["table3-1", "table3-3"]), did_you_mean("oval", ["square", "circle"])
    ("did you mean 'table3-3'?", '')
    """
    import difflib

    valid = [str(v) for v in valid]
    near = difflib.get_close_matches(str(name), valid, n=1)
    return f"did you mean {near[0]!r}?" if near else ""


class FabtilesDeprecationWarning(FutureWarning):
    """A name fabtiles still reads but has renamed (a profile's ``style`` is ``print_style``): the
    message says the new name. The command line prints it as a one-line note."""
