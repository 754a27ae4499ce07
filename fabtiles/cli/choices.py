"""The ``--format`` choices of the commands: the format table's, a format plugin's included.

Read when click first needs them (to check a value or write the help), so a plugin is
loaded only by a command that takes a format.
"""

from __future__ import annotations

import click


class FormatChoice(click.Choice):
    """A :class:`click.Choice` of the format table's offered formats whose fields have the values
    given (``FormatChoice(nests=True)``: the formats nested sheets are written in)."""

    def __init__(self, **wanted):
        self._wanted = wanted
        super().__init__((), case_sensitive=True)

    @property  # click sets the choices once; these are read each time
    def choices(self):
        from ..export.formats import names_where

        return names_where(**self._wanted)

    @choices.setter
    def choices(self, value) -> None:
        pass  # the table's, always
