"""``fabtiles install-inkscape-extension``: Extensions > Render > fabtiles, installed for the user's Inkscape."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import click

FILES = ("fabtiles_render.inx", "fabtiles_render.py")
"""The extension: its description (the dialog, the menu) and its script, as Inkscape's own come in pairs."""


def default_dest() -> Path:
    """The user's Inkscape extensions folder (``$XDG_CONFIG_HOME/inkscape/extensions``, by default under ~/.config)."""
    config = os.environ.get("XDG_CONFIG_HOME") or str(Path.home() / ".config")
    return Path(config) / "inkscape" / "extensions"


def install(dest, python: str = sys.executable) -> list:
    """Copy the extension into ``dest``, its script told to run fabtiles with ``python``; the paths written."""
    from importlib.resources import files

    from ..core.files import atomic_write

    dest = Path(dest)
    dest.mkdir(parents=True, exist_ok=True)
    written = []
    for name in FILES:
        # the script is kept as a template (.py.in): inkex is Inkscape's, so no test or linter imports it here
        text = files("fabtiles.inkscape").joinpath(name + ".in" if name.endswith(".py") else name).read_text()
        if name.endswith(".py"):  # Inkscape's python3 is not this one: the script calls back into this one
            text = text.replace("FABTILES_PYTHON = sys.executable", f"FABTILES_PYTHON = {python!r}", 1)
        written.append(atomic_write(dest / name, text))
    return written


@click.command("install-inkscape-extension")
@click.option(
    "--dest",
    type=click.Path(file_okay=False),
    default=None,
    help="The folder to install into (default: ~/.config/inkscape/extensions).",
)
def command(dest):
    """Install Extensions > Render > fabtiles into Inkscape (restart Inkscape to see it).

    The extension asks for a preset, the packing, its radius, the tile's size, frame and
    stroke, and inserts the pattern at true millimetres, one layer per laser layer.
    """
    for path in install(dest if dest is not None else default_dest()):
        click.echo(f"wrote {path}")
