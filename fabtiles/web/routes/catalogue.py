"""What the form is made from: the schema of the design keys, the presets, tilings, profiles and defaults,
the gallery."""

from __future__ import annotations

from fastapi import APIRouter
from fastapi.responses import Response

from ...machines import limits as _limits
from ...machines.profiles import bundled_profiles
from ...pattern.presets import PRESET_NOTES, PRESETS
from ..params import DEFAULTS
from ..schema_json import schema_json


def router(*, limits: _limits.Limits) -> APIRouter:
    """``/api/schema``, ``/api/presets``, ``/api/tilings``, ``/api/profiles``, ``/api/defaults``, ``/api/gallery``."""
    api = APIRouter()

    @api.get("/api/schema")
    def schema():
        """Every query parameter: its design key, type, range, default, unit, help and web widget."""
        return schema_json()

    @api.get("/api/presets")
    def presets():
        return {name: {**dict(p), "radii": list(p["radii"]), "note": PRESET_NOTES[name]} for name, p in PRESETS.items()}

    @api.get("/api/tilings")
    def tilings():
        """The tilings of packing=archimedean (the 11, then the two-uniform): name and polygon kinds (motif_<sides>)."""
        from ...pattern.tilings import ALL_TILINGS, NAMES, unit_cell

        return {t: {"name": NAMES[t], "kinds": sorted(set(unit_cell(t).sides.tolist()))} for t in ALL_TILINGS}

    @api.get("/api/profiles")
    def profiles():
        # the 2D cutters (lasers, routers, waterjets) share the laser menu: one key, laser_profile, takes them all
        return {"laser": list(bundled_profiles("laser")), "printer": list(bundled_profiles("printer"))}

    @api.get("/api/defaults")
    def defaults():
        return DEFAULTS

    @api.get("/api/gallery")
    def gallery_list():
        """The gallery: the paper's presets and the tilings' samples, each with its editor query."""
        from ..gallery import entries

        return [{"key": e.key, "title": e.title, "note": e.note, "query": e.query, "group": e.group} for e in entries()]

    @api.get("/api/gallery/{key}.svg")
    def gallery_thumbnail(key: str):
        """One gallery entry drawn by the preview code (cached: drawn once per process)."""
        from ..gallery import thumbnail

        return Response(
            thumbnail(key, limits=limits), media_type="image/svg+xml", headers={"Cache-Control": "public, max-age=3600"}
        )

    return api
