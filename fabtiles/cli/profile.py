"""``fabtiles profile``: list, show and copy the machine and material profiles.

The bundled profiles are starting points; a user's own settings go into a copy
(``fabtiles profile copy laser-3mm-plywood my-laser.toml``), edited and then
passed by path: ``laser_profile = "my-laser.toml"`` in a design, or
``fabtiles calibrate --profile my-laser.toml``.
"""

from __future__ import annotations

from pathlib import Path

import click

from ..core.errors import ProfileError
from ..machines.profiles import CutterProfile

KEY_OF_FAMILY = {"laser": "laser_profile", "printer": "printer_profile"}
"""The design key (``[output]``) that takes a profile of each family."""


@click.group("profile")
def command():
    """List, show and copy the machine and material profiles.

    \b
    fabtiles profile list
    fabtiles profile show laser-3mm-plywood
    fabtiles profile copy laser-3mm-plywood my-laser.toml
    """


@command.command("list")
def list_profiles():
    """List the bundled profiles by kind (laser, router, waterjet, printer), each with its description."""
    from ..machines.cutters import CUTTER_KINDS
    from ..machines.profiles import PRINTER, bundled_profiles, load_profile

    profiles = [load_profile(name) for name in bundled_profiles()]
    width = max(len(p.name) for p in profiles)
    for kind in (*CUTTER_KINDS, PRINTER):
        of_kind = [p for p in profiles if p.kind == kind]
        if not of_kind:
            continue
        click.echo(f"{kind}:")
        for p in of_kind:
            click.echo(f"  {p.name:<{width}}  {p.description}".rstrip())
    click.echo(
        "\nfabtiles profile show NAME prints one; fabtiles profile copy NAME my-NAME.toml makes your own copy to edit."
    )


@command.command("show")
@click.argument("name", metavar="NAME")
def show(name):
    """Print a profile's TOML: a bundled NAME, or the path of a profile file (checked as it is loaded).

    \b
    fabtiles profile show fdm-0.4mm
    fabtiles profile show my-laser.toml
    """
    from ..machines.profiles import profile_text

    text, _ = profile_text(name)
    click.echo(text, nl=not text.endswith("\n"))


@command.command("copy")
@click.argument("name", metavar="NAME")
@click.argument("path", metavar="PATH", type=click.Path(dir_okay=False))
@click.option("--force", is_flag=True, help="Overwrite PATH if it exists.")
def copy(name, path, force):
    """Write the TOML of profile NAME to PATH (a .toml file), to edit and pass by path.

    \b
    fabtiles profile copy laser-3mm-plywood my-laser.toml
    fabtiles profile copy fdm-0.4mm my-printer.toml --force
    """
    from ..core.files import atomic_write
    from ..machines.cutters import family
    from ..machines.profiles import load_profile, profile_text

    target = Path(path)
    if target.suffix.lower() != ".toml":
        raise ProfileError(
            f"the copy must be a .toml file (a name without it is taken for a bundled profile), "
            f"got {path!r}; try {str(target.with_suffix('.toml'))!r}"
        )
    if target.exists() and not force:
        raise ProfileError(f"{path} exists; pass --force to overwrite it, or give another PATH")
    text, profile = profile_text(name)
    head = (
        f"# A copy of profile {profile.name!r} (fabtiles profile copy): write your machine's and material's\n"
        f"# values into it, and pass it by path.\n"
    )
    try:
        atomic_write(target, head + text)
    except OSError as exc:
        raise ProfileError(f"cannot write {path!r}: {exc.strerror or exc}") from None
    load_profile(target)  # the copy loads as the original did
    key = KEY_OF_FAMILY[family(profile.kind)]
    use = [f'{key} = "{target.as_posix()}" in a design\'s [output]', f"--set output.{key}={target.as_posix()}"]
    if (
        key == "laser_profile" and isinstance(profile, CutterProfile) and profile.cutter.card
    ):  # the test card is a laser's
        use.append(f"fabtiles calibrate --profile {target.as_posix()}")
    click.echo(
        f"wrote {path}: a copy of {profile.kind} profile {profile.name}; edit its values, then use it by "
        f"path: {', or '.join(use)}"
    )
