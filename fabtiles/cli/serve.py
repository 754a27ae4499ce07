"""``fabtiles serve``: the local web app."""

from __future__ import annotations

import click


@click.command("serve")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to bind. Keep 127.0.0.1 unless other machines must reach it.")
@click.option("--port", default=8765, show_default=True, type=click.IntRange(1, 65535), help="TCP port.")
def command(host, port):
    """Serve the web app: change the parameters, watch the tile, download files.

    Opens nothing by itself; it prints the URL to open.
    """
    try:
        from ..web.app import serve
    except ModuleNotFoundError as exc:  # fastapi/uvicorn are the "web" extra
        raise click.ClickException(
            f"the web app needs {exc.name}: pip install 'fabtiles[web]'"
        ) from None
    shown = f"[{host}]" if ":" in host else host
    click.echo(f"fabtiles web app at http://{shown}:{port}/  (Ctrl+C stops it)")
    serve(host=host, port=port)
