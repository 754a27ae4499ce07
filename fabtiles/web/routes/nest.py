"""Nesting in the web app: tiles of several designs (the editor's queries) packed onto the cutter's sheets.

``POST /api/nest`` takes a JSON body (:func:`read_body`) and answers each sheet's
picture, parts and material use, and a link to the sheets' files as one zip
(``GET /api/nest/{key}.zip``), kept for the last :data:`KEPT` nests of the process:
the packer's result depends on its time budget, so the files are the very ones the
pictures show, not a second packing. ``POST /api/nest.zip`` answers the zip of the
same body directly (for scripts: no state). The work is
:func:`fabtiles.making.nesting.nest_bytes`, the build of ``fabtiles nest``, within the
web's limits (:data:`fabtiles.machines.limits.WEB_LIMITS`: parts and time).
"""

from __future__ import annotations

import dataclasses
import math
import secrets
import threading
from collections import OrderedDict
from urllib.parse import parse_qsl

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse, Response
from starlette.concurrency import run_in_threadpool

from ...core.errors import FabtilesError
from ...export.formats import names_where
from ...geometry.nest import ROTATIONS
from ...machines import limits as _limits
from ..building import design_of_query, field_of_param, user_message

DEFAULT_TIME_S = 3.0
"""The web's default packing time, seconds (the page's *Time*): a nest answers in a few seconds."""

KEPT = 8
"""How many nests' zips the process keeps for ``GET /api/nest/{key}.zip`` (the oldest go first)."""

_FIELDS = {
    "sheet_mm": "sheet",
    "gap_mm": "gap_mm",
    "rotations": "rotate",
    "time_s": "time_s",
    "count": "designs",
    "formats": "format",
}
"""An error's ``param`` in :func:`~fabtiles.making.nesting.plan_nest` -> the body's field it is about."""


class NestError(FabtilesError, ValueError):
    """A bad nest request; ``field`` names the body's field (``gap_mm``, ``designs[1].count``, ...)."""

    def __init__(self, message: str, field: str):
        super().__init__(message)
        self.field = field


def _number(body: dict, field: str, *, default=None):
    value = body.get(field, default)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise NestError(f"{field} must be a finite number, got {value!r}", field)
    return float(value)


def read_body(body, *, limits: _limits.Limits) -> dict:
    """The nest's designs and options from a request's JSON body, checked; errors name the body's field.

    The body: ``designs`` (a list of ``{"query": "<the editor's query>", "count": N}``),
    ``sheet`` (``[width, height]`` mm, or null: the cutter profile's bed), ``gap_mm`` (null:
    the kerf + 1 mm), ``rotate`` (``90``, ``180``, ``free``, ``none``), ``time_s`` (seconds,
    at most the web's limit) and ``format`` (a format nested sheets are written in: ``dxf``, ``svg``, ``lbrn2``).

    >>> read_body({"designs": [{"query": "preset=table3-1&width=40", "count": 0}]}, limits=_limits.WEB_LIMITS)
    Traceback (most recent call last):
    ...
    fabtiles.web.routes.nest.NestError: designs[0].count must be a whole number >= 1, got 0
    """
    _check_fields(body)
    designs = _designs(body.get("designs"), limits)
    sheet = _sheet_mm(body.get("sheet"))
    rotate = body.get("rotate", "90")
    if rotate not in ROTATIONS:
        raise NestError(f"rotate must be one of: {', '.join(ROTATIONS)}, got {rotate!r}", "rotate")
    fmt = body.get("format", "dxf")
    nests = names_where(nests=True)  # the format table's formats of nested sheets
    if fmt not in nests:
        raise NestError(f"format must be one of: {', '.join(nests)}, got {fmt!r}", "format")
    time_s = _number(body, "time_s", default=DEFAULT_TIME_S)
    if time_s <= 0 or time_s > limits.max_nest_time_s:
        raise NestError(
            f"time_s must be > 0 and at most {limits.max_nest_time_s:g} s here, got {time_s:g}; "
            f"give a time within that",
            "time_s",
        )
    parts = sum(n for _, n in designs)
    if parts > limits.max_nest_parts:
        raise NestError(
            f"the nest has {parts} parts, more than the limit of {limits.max_nest_parts} here; lower the counts",
            "designs",
        )
    return dict(
        designs=designs, sheet_mm=sheet, gap_mm=_number(body, "gap_mm"), rotations=rotate, time_s=time_s, format=fmt
    )


def _check_fields(body) -> None:
    """Refuse a body that is not a JSON object, or that has a field the nest does not know."""
    if not isinstance(body, dict):
        raise NestError(
            f"the body must be a JSON object with designs, sheet, gap_mm, rotate, time_s and format, "
            f"got {type(body).__name__}",
            "designs",
        )
    unknown = sorted(set(body) - {"designs", "sheet", "gap_mm", "rotate", "time_s", "format"})
    if unknown:
        raise NestError(
            f"{unknown[0]!r} is not a nest field, must be one of: designs, sheet, gap_mm, rotate, time_s, format",
            unknown[0],
        )


def _designs(entries, limits: _limits.Limits) -> list:
    """The body's designs, ``[(spec, count), ...]``: each entry's query made a design, two of one name told apart."""
    if not isinstance(entries, list) or not entries:
        raise NestError("designs must be a non-empty list of {query, count}: give at least one design", "designs")
    designs: list = []
    names: dict = {}
    for k, entry in enumerate(entries):
        spec, count = _design_entry(k, entry, limits)
        # two designs of one name (two edited ones, "custom") stay apart in the sheets' counts
        names[spec.name] = names.get(spec.name, 0) + 1
        if names[spec.name] > 1:
            spec = dataclasses.replace(spec, name=f"{spec.name}-{names[spec.name]}")
        designs.append((spec, count))
    return designs


def _design_entry(k: int, entry, limits: _limits.Limits) -> tuple:
    """Entry ``k`` of the body's designs checked: its design and its count."""
    where = f"designs[{k}]"
    if not isinstance(entry, dict) or not isinstance(entry.get("query", ""), str):
        raise NestError(f'{where} must be {{"query": "<the editor\'s query>", "count": N}}, got {entry!r:.80}', where)
    count = entry.get("count", 1)
    if isinstance(count, bool) or not isinstance(count, (int, float)) or not float(count).is_integer() or count < 1:
        raise NestError(f"{where}.count must be a whole number >= 1, got {count!r}", f"{where}.count")
    query = dict(parse_qsl(entry.get("query", "").lstrip("?"), keep_blank_values=True))
    try:
        _, spec, _ = design_of_query(query, limits=limits)
    except FabtilesError as exc:
        field = getattr(exc, "field", None) or field_of_param(getattr(exc, "key", None))
        raise NestError(
            f"design {k + 1}: {user_message(exc, field)}", f"{where}.{field}" if field else f"{where}.query"
        ) from exc
    return spec, int(count)


def _sheet_mm(sheet) -> tuple | None:
    """The body's sheet, ``(width, height)`` mm, checked (None: the cutter profile's bed)."""
    if sheet is None:
        return None
    if (
        not isinstance(sheet, list)
        or len(sheet) != 2
        or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0 for v in sheet)
    ):
        raise NestError(
            f"sheet must be [width, height] in mm, each > 0 (or null: the cutter profile's bed), got {sheet!r}",
            "sheet",
        )
    return (float(sheet[0]), float(sheet[1]))


def nest_files(body, *, limits: _limits.Limits):
    """The nest of a request's body: :class:`~fabtiles.making.nesting.NestedFiles`.

    Errors of the nest itself (a gap below the kerf, a part larger than the sheet) are
    raised as :class:`NestError` naming the body's field.
    """
    from ...making.nesting import nest_bytes

    asked = read_body(body, limits=limits)
    stem = "nest"  # the zip's files: nest-sheet-1.dxf, ... (the designs are several)
    try:
        return nest_bytes(
            asked["designs"],
            (asked["format"],),
            sheet_mm=asked["sheet_mm"],
            gap_mm=asked["gap_mm"],
            rotations=asked["rotations"],
            time_s=asked["time_s"],
            name=stem,
            limits=limits,
        )
    except FabtilesError as exc:
        field = getattr(exc, "field", None)
        if field is None:
            param = getattr(exc, "param", None)
            field = _FIELDS.get(param or "", "designs")  # the rest (profiles, inlay, segments) are the designs' own
        raise NestError(user_message(exc, None), field) from exc


def _answer(files, key: str) -> dict:
    job = files.job
    sheets = []
    for k, s in enumerate(job.sheets()):
        sheets.append(
            {
                "sheet": s["sheet"],
                "svg": job.picture(k),
                "material_use": s["material_use"],
                "parts": s["designs"],
                "count": s["parts"],
                "job": s["job"].get("line"),
                "files": s["files"],
            }
        )
    n = job.nesting
    return {
        "sheets": sheets,
        "files": [name for name, _ in files.files],
        "download": f"/api/nest/{key}.zip",
        "sheet_mm": list(n.sheet_mm),
        "gap_mm": n.gap_mm,
        "rotate": n.rotations,
        "parts": len(n.placements),
        "profile": job.options.cutter.name,
    }


def router(*, limits: _limits.Limits) -> APIRouter:
    """``/api/nest``, ``/api/nest.zip`` and ``/api/nest/{key}.zip``."""
    api = APIRouter()
    kept: OrderedDict = OrderedDict()
    lock = threading.Lock()

    async def body_of(request: Request):
        try:
            return await request.json()
        except ValueError:
            raise NestError(
                'the body must be JSON: {"designs": [{"query": ..., "count": N}], ...}', "designs"
            ) from None

    @api.post("/api/nest")
    async def nest(request: Request):
        """Nest the designs: each sheet's picture, parts and material use, and the link to its files' zip."""
        body = await body_of(request)
        files = await run_in_threadpool(nest_files, body, limits=limits)  # seconds of packing: off the event loop
        key = secrets.token_hex(8)
        with lock:
            kept[key] = files.zip_bytes()
            while len(kept) > KEPT:
                kept.popitem(last=False)
        return _answer(files, key)

    @api.post("/api/nest.zip")
    async def nest_zip(request: Request):
        """Nest the designs (the body of ``POST /api/nest``) and answer the sheets' files as one zip."""
        body = await body_of(request)
        files = await run_in_threadpool(nest_files, body, limits=limits)
        return Response(
            files.zip_bytes(),
            media_type="application/zip",
            headers={"Content-Disposition": 'attachment; filename="nest.zip"'},
        )

    @api.get("/api/nest/{key}.zip")
    def nest_download(key: str):
        """The files of a nest ``POST /api/nest`` made, while the process keeps it."""
        with lock:
            data = kept.get(key)
        if data is None:
            return JSONResponse(
                {"error": f"no nest {key!r} here (the app keeps the last {KEPT}); press Nest again", "field": None},
                status_code=404,
            )
        return Response(
            data, media_type="application/zip", headers={"Content-Disposition": 'attachment; filename="nest.zip"'}
        )

    return api
