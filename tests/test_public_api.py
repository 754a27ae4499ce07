"""The public API is exactly ``fabtiles.__all__``; scripts rely on these names (docs/file-conventions.md)."""

import fabtiles

EXPECTED = {
    "ArchimedeanPacking",
    "DesignError",
    "FabricationError",
    "FabtilesError",
    "LimitError",
    "ParameterError",
    "ProfileError",
    "HexPacking",
    "LaserProfile",
    "PrinterProfile",
    "Report",
    "SeamlessFit",
    "SquarePacking",
    "Star",
    "Tile",
    "load_design",
    "load_profile",
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
