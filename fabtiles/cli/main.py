"""Entry point of the ``fabtiles`` command.

A :class:`~fabtiles.FabtilesError` becomes one line on stderr and exit status 2;
anything else escaping is a bug and keeps its traceback. A build that wrote some
formats and refused others exits with :data:`REFUSED_EXIT`.
"""

from __future__ import annotations

import sys

import click

from ..core.errors import FabtilesError

REFUSED_EXIT = 3
"""The exit status of a build that wrote some of its formats and refused others (each named with its
reason); 2 is bad input, with nothing written, and 1 ``check``'s findings."""


class _Group(click.Group):
    """A click group that reports FabtilesError as one line and exit status 2."""

    def invoke(self, ctx):
        import warnings

        from ..core.errors import FabtilesDeprecationWarning

        others: list = []
        try:
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always", FabtilesDeprecationWarning)
                    try:
                        return super().invoke(ctx)
                    finally:  # a renamed key still read: one note each, saying the new name
                        for message in dict.fromkeys(
                            str(w.message) for w in caught if issubclass(w.category, FabtilesDeprecationWarning)
                        ):
                            click.echo(f"fabtiles: note: {message}", err=True)
                        others = [w for w in caught if not issubclass(w.category, FabtilesDeprecationWarning)]
            finally:  # anything else is shown as it would have been, once the recording has stopped
                for w in others:
                    warnings.showwarning(w.message, w.category, w.filename, w.lineno)
        except FabtilesError as exc:
            click.echo(f"fabtiles: error: {exc}", err=True)
            ctx.exit(2)


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="fabtiles")
def cli():
    """fabtiles: Islamic star patterns as laser-cut and 3D-printable tiles.

    Stars and rosettes on concentric circles and the tangent-circle tiling of
    Mansourifar & Shi, "Next Generation of Star Patterns", exported as DXF/SVG
    for laser cutters and STL/3MF/STEP for printers and CAD.
    """


def _float_list(text: str) -> tuple[float, ...]:
    try:
        return tuple(float(x) for x in text.replace(" ", "").split(",") if x != "")
    except ValueError:
        raise click.BadParameter(f"expected comma-separated numbers like 51,70,172, got {text!r}") from None


def motif_options(command):
    """The ``[motif]`` keys of the schema as options (``--preset``, ``--n``, ``--radii``, ...), in the schema's
    order."""
    from ..core import schema as _schema

    types = {"integer": int, "number": float}
    for k in reversed(_schema.section_keys("motif")):
        words = [k.help[:1].upper() + k.help[1:].replace("`", "")]
        if k.type == "numbers":
            words.append("comma-separated, e.g. 51,70,172")
        if k.range is not None and k.type == "integer":
            words.append(k.note or k.range.text(integer=True))
        if k.unit:
            words.append(k.unit)
        command = click.option(f"--{k.name}", k.name, type=types.get(k.type), help="; ".join(words) + ".")(command)
    return command


@cli.command()
def presets():
    """List the presets (the rows of the paper's tables) with their parameters, and the tilings."""
    from ..pattern.presets import PRESET_NOTES, PRESETS

    for name, p in PRESETS.items():
        radii = ",".join(f"{r:g}" for r in p["radii"])
        special = p["special"] if p["special"] is not None else "-"
        line = f"{name:<13} n={p['n']:<3} radii={radii:<16} alpha={p['alpha']:<3g} spr={p['spr']:<5g} special={special}"
        note = PRESET_NOTES[name]
        click.echo(line + (f"   ({note})" if note else ""))
    from ..pattern.tilings import ALL_TILINGS, NAMES, unit_cell

    click.echo('\nTilings ([packing] kind = "archimedean", tiling = "..."), motifs keyed by polygon sides:')
    for name in ALL_TILINGS:
        kinds = ",".join(map(str, sorted(set(unit_cell(name).sides.tolist()))))
        click.echo(f"{name:<24} {NAMES[name]:<40} polygons {kinds}")


@cli.command()
@motif_options
@click.option("--size", "size_mm", type=float, default=100.0, show_default=True, help="Width of the picture in mm.")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="SVG file to write.")
def star(preset, n, radii, alpha, spr, special, rotation, size_mm, output):
    """Draw one star or rosette as an SVG preview.

    \b
    fabtiles star --preset table1-part1 -o star.svg
    fabtiles star --n 8 --radii 51,70,172 -o star.svg
    """
    from ..core.schema import MOTIF_REQUIRED
    from ..export.motif_svg import write_motif_svg
    from ..pattern.star import Star

    given = {
        k: v for k, v in dict(n=n, alpha=alpha, spr=spr, special=special, rotation=rotation).items() if v is not None
    }
    if radii is not None:
        given["radii"] = _float_list(radii)
    if preset is not None:
        motif = Star.preset(preset).replace(**given)
    else:
        missing = [k for k in MOTIF_REQUIRED if k not in given]
        if missing:
            raise click.UsageError(f"give --preset, or --n and --radii (missing: --{', --'.join(missing)})")
        motif = Star(**given)
    if not output.lower().endswith(".svg"):
        raise click.BadParameter(f"the output must be an .svg file, got {output!r}", param_hint="-o")
    write_motif_svg(output, motif.segments(), size_mm=size_mm, title=repr(motif))
    click.echo(f"wrote {output} ({len(motif.segments())} segments)")


def _register_optional_commands():
    """Commands defined in their own modules (imported lazily by click when run)."""
    import importlib

    for module in (
        "new",
        "build",
        "nest",
        "batch",
        "sweep",
        "serve",
        "check",
        "calibrate",
        "profile",
        "plot",
        "inkscape",
    ):
        try:
            mod = importlib.import_module(f"{__package__}.{module}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__package__}.{module}":
                raise
            continue
        cli.add_command(mod.command)
        for extra in getattr(mod, "EXTRA_COMMANDS", ()):
            cli.add_command(getattr(mod, extra))


_register_optional_commands()


def _exit_on_sigterm(signum, frame):
    # Raise instead of dying, so every `finally` runs: temporary files and staging
    # folders are removed and no partial output is left behind.
    raise SystemExit(128 + signum)


def main(argv=None):
    """Run the CLI (console-script entry point)."""
    import signal

    if threading_is_main():
        signal.signal(signal.SIGTERM, _exit_on_sigterm)
    return cli.main(args=argv, prog_name="fabtiles")


def threading_is_main() -> bool:
    import threading

    return threading.current_thread() is threading.main_thread()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
