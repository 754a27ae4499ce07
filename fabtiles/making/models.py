"""The models of one build: the cut plan and the print model, each made once and shared by every file.

:class:`BuildOptions` gathers what a design (or a call) says about its machines: the
two profiles, loaded once, and the options of each. :class:`Models` makes, on
first use and then keeps, the cut plan (or an inlay kit's two plans, or a sheet's
plan) and the print model of one tile; every writer in the format table
(:mod:`fabtiles.export.formats`) is a pure function of one of them. So a build of
five formats runs the cutter's checks and contours once and the printer's checks
once, and each finding is reported once (``tests/making/test_one_model.py`` counts).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from ..core.errors import FabricationError, ParameterError
from ..core.report import Report
from ..core.schema import CALL_OPTIONS, FAMILIES, option_keys

if TYPE_CHECKING:
    from ..designs.colour import Colours
    from ..designs.design_file import SurfaceSpec
    from ..machines.profiles import CutterProfile, PrinterProfile
    from .cylinder import Cylinder

HEIGHT_FIELDS = tuple(k.name for k in option_keys("print") if k.unit == "mm")
"""The print heights, gathered in :attr:`BuildOptions.heights`."""

KIT_MODE = "inlay"


@dataclass(frozen=True)
class BuildOptions:
    """A build's machine settings: the profiles (loaded) and every option of the cut and the print.

    ``None`` means the profile's own value. Make one from a design with :meth:`of_design`.
    """

    cutter: CutterProfile
    """The cutter profile (:class:`~fabtiles.CutterProfile`), loaded."""
    printer: PrinterProfile
    """The printer profile (:class:`~fabtiles.PrinterProfile`), loaded."""
    laser_mode: str | None = None
    fill_small_holes: bool = True
    inlay_fit_mm: float | None = None
    inlay_pieces: str | None = None
    inlay_base: str | None = None
    tab_mm: float | None = None
    """Holding tabs' length along the outer cut (mm; None or 0: none)."""
    tabs_per_part: int | None = None
    dxf_version: str | None = None
    kerf_mm: float | None = None
    print_style: str | None = None
    heights: dict = field(default_factory=dict)
    pieces: bool = True
    """A tile larger than a machine's bed made as pieces that lock together (False: a cutter refuses
    it, a printer makes it whole with a ``bed_size`` warning)."""
    pieces_sheets: bool = False
    """A panel's pieces also nested onto bed-sized sheets."""
    inlay: bool = False
    """The deboss grooves filled as a second part of the print."""
    threemf_layout: str = "volumes"
    colours: Colours | None = None
    """The design's ``[colour]`` or the call's ``colours`` (:class:`~fabtiles.Colours`), or None: none given."""
    surface: SurfaceSpec | None = None
    """A cylinder's ``[surface]`` (the tile is its unrolled strip: :mod:`fabtiles.making.cylinder`), or None: a
    flat tile."""
    stamp: SurfaceSpec | None = None
    """A clay stamp's ``[surface]`` (the tile's relief on a block: :mod:`fabtiles.making.stamp`), or None."""

    @classmethod
    def of_design(cls, design) -> BuildOptions:
        """The options a validated design's ``[output]`` gives."""
        out = design.output
        keys = {k.name: k for family in FAMILIES for k in option_keys(family)}  # the design keys that are options
        values = {k.build.name: getattr(out, name) for name, k in keys.items()}
        from ..designs.design_file import profile_of

        return cls(
            cutter=profile_of(design, "laser"),
            printer=profile_of(design, "printer"),
            colours=design.colour,
            surface=design.surface if design.surface.cylinder else None,
            stamp=design.surface if design.surface.stamp else None,
            **cls.fields_of(values, *FAMILIES),
        )

    @staticmethod
    def fields_of(options: dict, *families: str) -> dict:
        """The fields given by build ``options`` (the export API's keywords: ``mode``, ``style``, ``base_mm``)
        of ``families``, named as the design's keys (``laser_mode``, ``print_style``, in ``heights``).

        >>> BuildOptions.fields_of({"mode": "inlay", "base_mm": 2.0, "layout": None}, "cut", "3mf")
        {'laser_mode': 'inlay', 'heights': {'base_mm': 2.0}}
        """
        out: dict = {}
        wanted = {f for family in families for f in (("print", "3mf") if family == "3mf" else (family,))}
        calls = {o.name for o in CALL_OPTIONS if set(o.families) & wanted}
        for name in calls & set(options):
            out[name] = options[name]  # the call's own options (dxf_version, kerf_mm) keep their names
        if out.get("colours") is not None:
            out["colours"] = _colours(out["colours"])
        for family in families:
            for k in option_keys(family):
                value = options.get(k.build.name)
                if value is None:
                    continue  # not given: the field's default (the profile's)
                if k.name in HEIGHT_FIELDS:
                    out.setdefault("heights", {})[k.name] = value
                else:
                    out[k.name] = value
        return out

    @property
    def mode(self) -> str:
        """The cutter's mode: the option's, else the profile's."""
        return self.laser_mode or self.cutter.mode

    @property
    def kit(self) -> bool:
        """Whether the cutter's files are an inlay kit (two files per format)."""
        return self.mode == KIT_MODE


def _colours(value):
    """The API's ``colours=``: a :class:`~fabtiles.Colours`, or a dict of its keys made into one.

    >>> _colours({"by": "shape"}).by
    'shape'
    >>> _colours("iznik")
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: colours must be a fabtiles.Colours (or a dict of its keys: by, palette, band_colour, base_colour, faces, shaded, shades), got 'iznik'
    """  # noqa: E501 - a doctest's lines are as Python prints them
    from ..core.schema import names
    from ..designs.colour import Colours

    if isinstance(value, Colours):
        return value
    keys = names("colour")
    if isinstance(value, dict) and set(value) <= set(keys):
        return Colours(**value)
    raise ParameterError(
        f"colours must be a fabtiles.Colours (or a dict of its keys: {', '.join(keys)}), got {value!r}", param="colours"
    )


class BuildModels(Protocol):
    """What :func:`~fabtiles.making.pipeline.write_files` asks of a build's models: a tile's
    (:class:`Models`) or a nest's sheets."""

    options: BuildOptions

    def model(self, family: str) -> Any:
        """The model format family ``family`` is written from (:class:`~fabtiles.export.formats.CutModel`,
        :class:`~fabtiles.export.formats.PrintModelProtocol`)."""
        ...

    def reports(self, files=()) -> list[tuple[str, Report]]:
        """``(label, report)`` of each model made, once each; ``files``: the build's file reports."""
        ...


class Models:
    """The cut plan and print model of one tile (or one sheet), each made on first use, once.

    Parameters
    ----------
    tile : TileGeometry
        The tile (its region, outline, centre-lines, stroke).
    options : BuildOptions
    sheet : Sheet, optional
        A laid-out sheet (:func:`~fabtiles.geometry.sheet.layout_sheet`): the cut plan
        is the sheet's; a sheet has no print model.
    checking : bool
        Make the models for ``fabtiles check``: the inlay kit's plans are not made
        (its lattice is checked as a pierced tile), nothing is meshed.
    cut_region, print_region : tuple, optional
        The regions the models are made from, when given rather than made from the tile
        (a bare region's, a window of the tile): see :attr:`cut_region` and :attr:`print_region`.
    """

    def __init__(
        self, tile, options: BuildOptions, *, sheet=None, checking: bool = False, cut_region=None, print_region=None
    ):
        self.tile = tile
        self.options = options
        self.sheet = sheet
        self.checking = checking
        self._cut_region = cut_region
        self._print_region = print_region
        self._window = print_region is not None  # a window of the tile (the 3D view's): never in pieces
        self._cut = None
        self._print = None

    def _material(self, region):
        """``region``, or a :class:`~fabtiles.FabricationError` when it is empty (no file of nothing)."""
        if region is None or region.is_empty:
            raise FabricationError(
                "the tile holds no material: every stroke of its pattern falls outside the outline; "
                "add a frame, make the tile larger, or make the packing radius smaller"
            )
        return region

    # ------------------------------------------------------------------ the cutter

    @property
    def cut_region(self):
        """``(region, centrelines)`` the cutter's files are made from
        (see :func:`~fabtiles.geometry.machine_geometry.cut_geometry`), made once."""
        from ..geometry.machine_geometry import cut_geometry

        if self._cut_region is None:
            o = self.options
            mode = "pierced" if o.kit else o.laser_mode
            if self.sheet is not None:
                self._cut_region = (self.sheet.region, self.sheet.centrelines)
            else:
                self._cut_region = cut_geometry(self.tile, profile=o.cutter, mode=mode, lines=not o.kit)
        return self._cut_region

    @property
    def cut(self):
        """The cut model (:class:`~fabtiles.export.formats.CutModel`), made on first use, once: the cut plan
        (:class:`~fabtiles.geometry.cut_plan.CutPlan`), or an inlay kit's two
        (:class:`~fabtiles.geometry.cut_plan.KitPlans`)."""
        if self._cut is None:
            self._cut = self._make_cut()
        return self._cut

    def _make_cut(self):
        from ..export.formats import check_dxf_version
        from ..geometry.cut_plan import CutOptions, KitOptions, plan_cut, plan_kit

        o = self.options
        if o.surface is not None or o.stamp is not None:
            shape = "cylinder" if o.surface is not None else "stamp"
            raise FabricationError(
                f'[surface] shape = "{shape}" is printed, not cut: it makes no cutter file; '
                "ask for a print format (stl, 3mf)"
            )
        shades = self.shades()
        region, centrelines = self.cut_region
        self._material(self.tile.region() if self.sheet is None else region)
        outline = self.sheet.outline if self.sheet is not None else self.tile.outline_shape()
        if o.kit and self.checking:  # the check looks at the lattice as a pierced tile
            return plan_cut(
                region,
                outline,
                CutOptions.of(
                    profile=o.cutter,
                    mode="pierced",
                    kerf_mm=o.kerf_mm,
                    fill_small_holes=o.fill_small_holes,
                    stroke=self.tile.stroke,
                    tab_mm=o.tab_mm,
                    tabs_per_part=o.tabs_per_part,
                ),
            )
        if o.kit and self.sheet is None:
            kit_options = KitOptions.of(
                profile=o.cutter,
                inlay_fit_mm=o.inlay_fit_mm,
                inlay_base=o.inlay_base or "pierced",
                kerf_mm=o.kerf_mm,
                stroke=self.tile.stroke,
                tab_mm=o.tab_mm,
                tabs_per_part=o.tabs_per_part,
            )
            check_dxf_version(o.dxf_version)  # the files' option, refused with the plan's before the work
            kit = plan_kit(region, outline, kit_options, colours=self.kit_colours() if self.coloured else ())
            if self.coloured:
                from ..geometry.kit_nesting import class_letters

                # a class none of whose faces became a piece (all too small: filled) is cut in no wood
                classes = self.face_classes
                cut = set(
                    class_letters(kit.kit.holes, classes.faces, classes.labels, [c.letter for c in classes.classes])
                )
                filled = frozenset(c.letter for c in classes.classes if c.letter not in cut)
                report = kit.report.extended(
                    notes=[f"lattice in {self.colouring.band.name} (the band colour)"],
                    face_classes=self.face_class_stats(filled),
                )
                kit = replace(kit, lattice=replace(kit.lattice, report=report))
            if (o.inlay_pieces or "registration") == "nested":
                from ..geometry.kit_nesting import class_letters, nest_kit

                classes = (
                    self.face_classes
                    if self.options.colours is not None and self.options.colours.by == "shape"
                    else self._shape_classes
                )
                letters = class_letters(
                    kit.kit.holes, classes.faces, classes.labels, [c.letter for c in classes.classes]
                )
                kit = nest_kit(kit, letters_of_holes=letters, tabs=(o.tab_mm, o.tabs_per_part))
            return kit
        if o.kit:
            raise ParameterError(
                "a sheet of inlay kits is not laid out; write the kit of one tile (drop --sheet "
                'and --copies) or choose laser_mode = "pierced"',
                param="laser_mode",
            )
        cut_options = CutOptions.of(
            profile=o.cutter,
            mode=o.laser_mode,
            kerf_mm=o.kerf_mm,
            fill_small_holes=o.fill_small_holes,
            stroke=self.tile.stroke,
            tab_mm=o.tab_mm,
            tabs_per_part=o.tabs_per_part,
        )
        check_dxf_version(o.dxf_version)  # the files' option, refused with the plan's before the work
        if self.sheet is None and o.pieces and not shades:
            from .pieces import pieces_model, too_big, with_sheets

            if too_big(outline, o.cutter):  # cut as pieces that lock together, each on the bed
                pieces = pieces_model(self.tile, region, centrelines, o.cutter, cut_options)
                return with_sheets(pieces) if o.pieces_sheets else pieces
        plan = plan_cut(region, outline, cut_options, centrelines=centrelines, shades=shades)
        return self._with_notes(plan, shades)

    def _with_notes(self, plan, shades):
        """``plan`` with the report's lines a tile's plan alone cannot say: its shaded classes, and a
        sheet's tiles."""
        o = self.options
        if shades:
            plan = replace(plan, report=plan.report.extended(notes=self._shade_notes(plan)))
        if self.sheet is not None:  # how many tiles, which the files' summary does not show otherwise
            n = len(self.sheet.offsets)
            bed = " x ".join(f"{v:g}" for v in o.cutter.bed_mm)
            used = " x ".join(f"{v:.1f}" for v in self.sheet.size)
            note = (
                f"laid {n} {'tile' if n == 1 else 'tiles'} on the {bed} mm bed of {o.cutter.kind} "
                f"profile {o.cutter.name!r} ({used} mm used)"
            )
            plan = replace(plan, report=plan.report.extended(notes=[note]))
        return plan

    # ------------------------------------------------------------------ the colours

    def shades(self) -> tuple:
        """A shaded engraving's layers: ``((Layer, faces), ...)`` of the classes ``[colour] shaded``
        names (:mod:`~fabtiles.geometry.shades`); none when it names none."""
        from ..geometry.shades import shade_layers

        spec = self.options.colours
        if spec is None or not spec.shaded.strip():
            return ()
        if self.options.kit or self.sheet is not None:
            what = "an inlay kit" if self.options.kit else "a sheet of tiles"
            raise ParameterError(
                f"[colour] shaded = {spec.shaded!r} shades one tile's faces, not {what}: "
                'write one tile (laser_mode "pierced", "score" or "engrave", no --sheet or --copies) or drop it',
                param="colour.shaded",
            )
        classes = self.face_classes
        if not classes.classes:  # the letters are checked against the classes, and there are none
            raise ParameterError(
                f"[colour] shaded = {spec.shaded!r} names face classes, and this design has no faces (its bands "
                "cover the whole tile): drop it, or make the stroke narrower",
                param="colour.shaded",
            )
        letters = spec.engraved([c.letter for c in classes.classes])
        colours = [(letter, self.colouring.face(letter).srgb) for letter in letters]
        layers = shade_layers(self.options.cutter, colours, spec.shade_overrides())
        return tuple((layer, classes.of(letter)) for letter, layer in layers)

    def _shade_notes(self, plan) -> list:
        """The report's lines on a shaded engraving: each class's layer and settings, and the classes that
        came out alike."""
        from ..geometry.shades import shared_powers

        notes = []
        named = [(layer.layer.name.removeprefix("SHADE_"), layer.layer) for layer in plan.layers]
        named = [(k, layer) for k, layer in named if layer.name.startswith("SHADE_")]
        for letter, layer in named:
            colour = self.colouring.face(letter)
            notes.append(
                f"class {letter} ({colour.name}) engraved on layer {layer.name}: {layer.power_pct:g} % at "
                f"{layer.speed_mm_s:g} mm/s, line interval {layer.line_interval_mm:g} mm, {layer.passes} pass"
                f"{'es' if layer.passes != 1 else ''}"
            )
        for group in shared_powers(named):
            notes.append(
                f"classes {', '.join(group)} engrave alike (the same derived settings): widen the engrave layer's "
                "power_range_pct or set their power_pct in [colour.shades]"
            )
        return notes

    @cached_property
    def face_classes(self):
        """The tile's faces grouped into classes (:func:`~fabtiles.geometry.faces.face_classes`), by the
        design's ``[colour] by`` (one class when no colours are given)."""
        from ..geometry.faces import face_classes

        spec = self.options.colours
        return face_classes(self.tile, by=spec.by if spec is not None else "none")

    @cached_property
    def _shape_classes(self):
        """The faces classed by shape whatever the colours say: a nested kit's letters."""
        from ..geometry.faces import face_classes

        return face_classes(self.tile, by="shape")

    @cached_property
    def colouring(self):
        """The colours of the band, the base and each face class (:class:`~fabtiles.designs.colour.Colouring`)."""
        from ..designs.colour import Colours

        spec = self.options.colours if self.options.colours is not None else Colours(given=False)
        try:
            return spec.colouring(tuple(c.letter for c in self.face_classes.classes) or ("A",))
        except ParameterError as exc:
            raise ParameterError(
                f"[colour.faces] {exc}" if (exc.param or "").startswith("faces") else f"[colour] {exc}",
                param=f"colour.{exc.param}",
            ) from None

    @property
    def coloured(self) -> bool:
        """Whether colours were asked for (a ``[colour]`` section, the API's ``colours=``)."""
        return self.options.colours is not None and self.options.colours.given

    def picture_colours(self) -> dict:
        """:func:`~fabtiles.export.preview_svg.tile_svg`'s colours: the bands', and each class's faces
        (nothing when no colours were asked for)."""
        spec = self.options.colours
        if spec is None or not self.coloured:
            return {}
        classes, colours = self.face_classes, self.colouring
        if spec.shaded.strip() and not self.options.kit and self.sheet is None:
            return self._burnt_colours()
        return dict(
            fill=colours.band.hex,
            faces=tuple((c.letter, classes.of(c.letter), colours.face(c.letter).hex) for c in classes.classes),
        )

    def _burnt_colours(self) -> dict:
        """A shaded engraving's picture colours: each shaded class burnt at its power on bare wood, the
        bands engraved in the engrave mode (else wood), a class a pierced cut cuts out left open."""
        from ..geometry.laser_checks import engrave_layer
        from ..geometry.shades import WOOD, burn_colour

        darkest = engrave_layer(self.options.cutter).shade_range_pct[1]
        burnt = {layer.name.removeprefix("SHADE_"): layer.power_pct for layer, _ in self.shades()}
        mode = self.options.mode
        fill = burn_colour(engrave_layer(self.options.cutter).power_pct, darkest) if mode == "engrave" else WOOD
        classes = self.face_classes
        faces = tuple(
            (c.letter, classes.of(c.letter), burn_colour(burnt[c.letter], darkest) if c.letter in burnt else WOOD)
            for c in classes.classes
            if c.letter in burnt or mode != "pierced"
        )
        return dict(fill=fill, faces=faces)

    def filled_classes(self, region) -> frozenset:
        """The letters of the classes none of whose faces is an opening of ``region``: every face filled
        with the bands (``fill_small_holes``: narrower than the machine makes), so the class prints in no
        colour of its own."""
        import shapely

        classes = self.face_classes
        if region is None or not len(classes.faces):
            return frozenset()
        probe = shapely.get_coordinates(shapely.point_on_surface(np.asarray(classes.faces, dtype=object)))
        shapely.prepare(region)
        covered = shapely.contains_xy(region, probe[:, 0], probe[:, 1])
        return frozenset(c.letter for k, c in enumerate(classes.classes) if covered[classes.labels == k].all())

    def face_class_stats(self, filled=frozenset()) -> list:
        """The face classes for a report: letter, count, description, area and colour name; a class of
        ``filled`` (:meth:`filled_classes`) says so in place of a colour."""
        return [
            dict(c, colour=None, filled=True)
            if c["letter"] in filled
            else dict(c, colour=self.colouring.face(c["letter"]).name)
            for c in self.face_classes.stats()
        ]

    def kit_colours(self) -> tuple:
        """A coloured kit's woods: ``((colour name, faces), ...)``, one per distinct face colour, in class order."""
        colours, classes = self.colouring, self.face_classes
        out: dict = {}
        for c in classes.classes:
            colour = colours.face(c.letter)
            name, faces = out.get(colour.hex, (colour.name, []))
            faces.extend(classes.faces[classes.labels == classes.classes.index(c)])
            out[colour.hex] = (name, faces)
        return tuple((name, tuple(faces)) for name, faces in out.values())

    def mosaic_specs(self, filled=frozenset()) -> tuple:
        """A mosaic's parts, one per distinct colour (base, bands, then the classes'), in material order;
        the classes of ``filled`` (:meth:`filled_classes`) print with the bands, in no part of their own."""
        from ..designs.colour import check_materials
        from ..solid.parts import MosaicPart

        colours, classes = self.colouring, self.face_classes
        printed = tuple((k, v) for k, v in colours.faces if k not in filled)
        materials = tuple({c.hex: c for c in (colours.base, colours.band, *(v for _, v in printed))}.values())
        check_materials(materials)
        specs = []
        for c in materials:
            letters = [k for k, v in printed if v.hex == c.hex]
            holds = (["base"] if colours.base.hex == c.hex else []) + (["bands"] if colours.band.hex == c.hex else [])
            index = [i for i, fc in enumerate(classes.classes) if fc.letter in letters]
            faces = tuple(classes.faces[np.isin(classes.labels, index)]) if index else ()
            specs.append(
                MosaicPart(f"{c.name} ({', '.join(holds + letters)})", "base" in holds, "bands" in holds, faces, c)
            )
        return tuple(specs)

    def print_parts_line(self, region, style: str) -> str:
        """What the print of ``region`` (the print's material, small openings filled) is made of, in a line:
        its parts and the filaments they take (a mosaic's parts are its colours).
        """
        from ..solid.parts import part_kinds
        from ..solid.print_model import PART_MATERIALS

        if style == "mosaic":
            names = [s.name for s in self.mosaic_specs(self.filled_classes(region))]
            return f"print: {len(names)} part{'s' if len(names) != 1 else ''}, one filament each: {', '.join(names)}"
        names = list(part_kinds(style, single=False, inlay=self.options.inlay))
        if self.coloured:
            c = self.colouring
            colours = {n: (c.band if n in ("pattern", "inlay") else c.base) for n in names}
            shown = [f"{colours[n].name} ({n})" for n in names]
            n_fil = len({colours[n].hex for n in names})
        else:
            shown, n_fil = names, len({PART_MATERIALS[n].extruder for n in names}) if len(names) > 1 else 1
        return (
            f"print: {len(names)} part{'s' if len(names) != 1 else ''} ({', '.join(shown)}), "
            f"{n_fil} filament{'s' if n_fil != 1 else ''}"
        )

    # ------------------------------------------------------------------ the printer

    @property
    def print_region(self):
        """``(region, dips)`` the print is made from
        (see :func:`~fabtiles.geometry.machine_geometry.print_geometry`), made once."""
        from ..geometry.machine_geometry import print_geometry

        if self._print_region is None:
            self._print_region = print_geometry(self.tile, profile=self.options.printer, style=self.options.print_style)
        return self._print_region

    @property
    def print(self):
        """The print model (:class:`~fabtiles.solid.print_model.PrintModel`), made on first use, once; its
        meshes are made on first use."""
        if self._print is None:
            self._print = self._make_print()
        return self._print

    @cached_property
    def cylinder(self) -> Cylinder | None:
        """The cylinder the tile's strip is wrapped into (:class:`~fabtiles.making.cylinder.Cylinder`), its
        values checked; None for a flat tile."""
        from .cylinder import cylinder_of

        if self.options.surface is None:
            return None
        return cylinder_of(self.options.surface, self.options, self.tile.width_mm)

    def flat_print(self, region, dips, *, style, heights, coloured=None, **extra):
        """The flat print model of ``region`` on the tile's outline with the build's printer, stroke, filling of
        small openings, inlay and colours: the one call a tile, a cylinder's strip and a stamp's face share.

        ``coloured``: colour the parts (default: when the design gives colours); ``extra``: more keywords of
        :func:`~fabtiles.solid.print_model.print_model` (a strip's ``period_mm``).
        """
        from ..solid.print_model import print_model

        o = self.options
        coloured = self.coloured if coloured is None else coloured
        return print_model(
            region,
            self.tile.outline_shape(),
            profile=o.printer,
            style=style,
            stroke=self.tile.stroke,
            fill_small_holes=o.fill_small_holes,
            inlay=o.inlay,
            dips=dips,
            colours=self.colouring if coloured else None,
            **extra,
            **heights,
        )

    def _make_print(self):
        if self.cylinder is not None:
            from .cylinder import cylinder_print

            self._material(self.print_region[0])
            return cylinder_print(self, self.cylinder)
        if self.options.stamp is not None:
            from .stamp import stamp_print

            self._material(self.print_region[0])
            return stamp_print(self)
        if self.print_in_pieces:
            return self._make_print_pieces()
        o = self.options
        region, dips = self.print_region
        self._material(region)
        style = o.print_style or o.printer.print_style
        given = self.coloured
        model = self.flat_print(
            region, dips, style=o.print_style, heights=o.heights, coloured=given or style == "mosaic"
        )
        if style != "mosaic" and not given:
            return model
        filled = self.filled_classes(model.region) if o.fill_small_holes else frozenset()
        # the parts are made lazily: a mosaic's take the classes left open by the print's filling
        return model.with_classes(
            self.mosaic_specs(filled) if style == "mosaic" else (),
            model.report.extended(face_classes=self.face_class_stats(filled)),
        )

    # ------------------------------------------------------------------ a print larger than the bed

    @property
    def print_in_pieces(self) -> bool:
        """Whether the print is made as pieces: ``pieces`` is on and the outline fits the printer's bed
        neither way round (a tile that fits is printed whole, as ever)."""
        from ..geometry.laser_checks import fits_bed

        o = self.options
        if not o.pieces or self.sheet is not None or self._window or o.surface is not None or o.stamp is not None:
            return False  # a cylinder or a stamp is printed whole (a cylinder too wide refused: check_cylinder)
        x0, y0, x1, y1 = self.tile.outline_shape().bounds
        return not fits_bed(x1 - x0, y1 - y0, self.options.printer.bed_mm)

    def _make_print_pieces(self):
        """The print as pieces (:class:`~fabtiles.making.print_pieces.PrintPieces`), split for the printer's bed."""
        from ..geometry.print_checks import print_region
        from ..geometry.stack import resolve_stack
        from .pieces import pattern_period
        from .print_pieces import print_pieces

        o = self.options
        region, dips = self.print_region
        self._material(region)
        outline = self.tile.outline_shape()
        style = o.print_style or o.printer.print_style
        mosaic = ()
        if style == "mosaic":
            stack = resolve_stack(o.printer, style, **o.heights)
            filled_region = print_region(region, outline, o.printer, stack.style, fill_small_holes=o.fill_small_holes)[
                0
            ]
            mosaic = self.mosaic_specs(self.filled_classes(filled_region) if o.fill_small_holes else frozenset())
        period, origin = pattern_period(self.tile)
        return print_pieces(
            region,
            outline,
            profile=o.printer,
            style=o.print_style,
            heights=o.heights,
            stroke=self.tile.stroke,
            fill_small_holes=o.fill_small_holes,
            inlay=o.inlay,
            dips=dips,
            colours=self.colouring if self.coloured or style == "mosaic" else None,
            mosaic=mosaic,
            period_mm=period,
            origin=origin,
        )

    def model(self, family: str):
        """The model a format family is written from: ``"cut"`` or ``"print"``."""
        return self.cut if family == "cut" else self.print

    def made(self, family: str) -> bool:
        """Whether the model of ``family`` (``"cut"`` or ``"print"``) has been made."""
        return (self._cut if family == "cut" else self._print) is not None

    def reports(self, files=()) -> list[tuple[str, Report]]:
        """``(label, report)`` of each model made so far: one set of findings per model. ``files``: the
        file reports of a build; the print model's says the filament, as the first print file measured it."""
        from ..geometry.cut_plan import KitPlans

        out = []
        if self.made("cut"):
            label = f"{self.options.cutter.kind} {self.options.cutter.name}"
            out.append((label + (" (inlay kit)" if isinstance(self.cut, KitPlans) else ""), self.cut.report))
        if self.made("print"):
            report = self.print.report
            material = next((r.stats["material"] for r in files if "material" in r.stats), None)
            if material is not None and self.print_in_pieces:  # every piece's, not the first file's
                material = self.print.material()
            if material is not None and "material" not in report.stats:
                report = report.extended(material=material)
            out.append((f"printer {self.options.printer.name}", report))
        return out
