"""The public API is exactly ``fabtiles.__all__``; scripts rely on these names (docs/file-conventions.md)."""

import fabtiles

EXPECTED = {
    "ArchimedeanPacking",
    "Colours",
    "CutterProfile",
    "DesignError",
    "FabricationError",
    "FabtilesError",
    "Format",  # a format plugin's row (docs/architecture.md)
    "GirihPacking",
    "LimitError",
    "ParameterError",
    "ProfileError",
    "HexPacking",
    "LaserProfile",  # the former name of CutterProfile, kept so scripts keep working
    "PrinterProfile",
    "Report",
    "SeamlessFit",
    "SquarePacking",
    "Star",
    "Tile",
    "TilingPacking",  # ArchimedeanPacking is its former name, kept so scripts keep working
    "load_design",
    "load_profile",
    "nest",
    "seamless_fit",
    "seamless_radius",
    "straight_radii",
}


def test_all_is_pinned():
    assert set(fabtiles.__all__) == EXPECTED
    assert len(fabtiles.__all__) == len(EXPECTED)


def test_every_public_name_exists():
    for name in fabtiles.__all__:
        assert getattr(fabtiles, name) is not None


def test_error_tree():
    for leaf in ("ParameterError", "ProfileError", "DesignError", "FabricationError", "LimitError"):
        cls = getattr(fabtiles, leaf)
        assert issubclass(cls, fabtiles.FabtilesError) and issubclass(cls, ValueError)


def test_laser_profile_is_the_cutter_profile():
    assert fabtiles.LaserProfile is fabtiles.CutterProfile
    router = fabtiles.load_profile("router-6mm-mdf")
    assert isinstance(router, fabtiles.LaserProfile) and isinstance(router, fabtiles.CutterProfile)


def test_help_of_tile_export_lists_every_option_the_call_takes():
    """help(Tile.export) names each keyword option the export API accepts (from the schema), so it cannot drift."""
    import pydoc

    from fabtiles.core import schema as _schema

    text = pydoc.render_doc(fabtiles.Tile.export, renderer=pydoc.plaintext)
    for family in ("cut", "print", "3mf"):
        for name in _schema.build_options(family):
            assert f"    {name} : " in text, name
    assert "Options for cutter files (.dxf, .svg, .lbrn2):" in text and "Options for .3mf files only:" in text
