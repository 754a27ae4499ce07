"""``fabtiles serve``: the local web app."""

from __future__ import annotations

from pathlib import Path

import click

EXTRA_COMMANDS = ("install_viewer",)
"""Commands of this module besides `command`."""


@click.command("serve")
@click.option(
    "--host",
    default="127.0.0.1",
    show_default=True,
    help="Address to bind. Keep 127.0.0.1 unless other machines must reach it.",
)
@click.option("--port", default=8765, show_default=True, type=click.IntRange(1, 65535), help="TCP port.")
def command(host, port):
    """Serve the web app: change the parameters, watch the tile, download files.

    Opens nothing by itself; it prints the URL to open.
    """
    try:
        from ..web.app import serve
    except ModuleNotFoundError as exc:  # fastapi/uvicorn are the "web" extra
        raise click.ClickException(f"the web app needs {exc.name}: pip install 'fabtiles[web]'") from None
    shown = f"[{host}]" if ":" in host else host
    click.echo(f"fabtiles web app at http://{shown}:{port}/  (Ctrl+C stops it)")
    serve(host=host, port=port)


@click.command("install-viewer")
@click.option(
    "--tarball",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
    default=None,
    help="The npm tarball of three (`npm pack three@VERSION`), for a machine without the internet.",
)
def install_viewer(tarball):
    """Install three.js, the web app's 3D view, into the package (once; then the app works offline).

    Downloads the pinned npm tarball of three.js, checks its sha512 against npm's
    integrity, and extracts the few modules the view imports with their licence.
    """
    from ..web import viewer_files

    if viewer_files.installed() and tarball is None:
        click.echo(f"three.js {viewer_files.VERSION} is already installed in {viewer_files.VENDOR}")
        return
    written = viewer_files.install(tarball.read_bytes() if tarball else None)
    size = sum(p.stat().st_size for p in written)
    click.echo(
        f"installed three.js {viewer_files.VERSION} ({len(written)} files, {size / 1e6:.1f} MB) "
        f"in {viewer_files.VENDOR}"
    )
