"""Star and the packings are read-only values (like Tile): hashable, picklable, safely cached."""

from __future__ import annotations

import copy
import pickle
from dataclasses import FrozenInstanceError

import numpy as np
import pytest

from fabtiles import HexPacking, ParameterError, SquarePacking, Star

STAR = Star(n=8, radii=(51, 70, 172), alpha=10, spr=5, special=2, rotation=3)


def packings():
    return [
        HexPacking(radius=10, motif=Star.preset("table3-3")),
        SquarePacking(radius=7, motif=STAR, gap_motif=Star(n=4, radii=(1, 2)), outline_circles=True, fill=0.9),
    ]


# A name that is not a field: before Python 3.13 a frozen dataclass with slots refuses it with a
# TypeError (a CPython bug in the __setattr__ it writes) rather than a FrozenInstanceError.
NOT_A_FIELD = (FrozenInstanceError, TypeError)


@pytest.mark.parametrize("name", ["n", "radii", "alpha", "spr", "special", "rotation", "_segments", "new"])
def test_star_attributes_cannot_be_assigned(name):
    star = Star(n=8, radii=(1, 2))
    before = star.segments()
    if name in star.params():
        with pytest.raises(FrozenInstanceError, match=f"cannot assign to field '{name}'"):
            setattr(star, name, 5)
        with pytest.raises(FrozenInstanceError, match=f"cannot delete field '{name}'"):
            delattr(star, name)
    else:
        with pytest.raises(NOT_A_FIELD):
            setattr(star, name, 5)
        with pytest.raises(NOT_A_FIELD):
            delattr(star, name)
    assert np.array_equal(star.segments(), before) and star == Star(n=8, radii=(1, 2))


@pytest.mark.parametrize("name", ["radius", "motif", "gap_motif", "outline_circles", "fill", "_unit", "kind"])
def test_packing_attributes_cannot_be_assigned(name):
    for p in packings():
        before = p.replace()
        if name in p.params():
            with pytest.raises(FrozenInstanceError, match=f"cannot assign to field '{name}'"):
                setattr(p, name, 5)
            with pytest.raises(FrozenInstanceError, match=f"cannot delete field '{name}'"):
                delattr(p, name)
        else:
            with pytest.raises(NOT_A_FIELD):
                setattr(p, name, 5)
        assert p == before and p.kind == type(p).kind


def test_segments_cache_cannot_be_changed_from_outside():
    star = Star(n=8, radii=(1, 2))
    seg = star.segments()
    seg[:] = 0  # a copy: the star keeps its own
    assert star.segments().any()
    with pytest.raises(ValueError, match="read-only"):
        star._segments[0, 0, 0] = 1  # the cache itself is frozen
    p = packings()[0]
    unit = p.placed_motif()
    unit[:] = 0
    assert p.placed_motif().any() and p.segments((0, 0, 20, 20)).any()


@pytest.mark.parametrize("value", [STAR, *packings()], ids=["star", "hex", "square"])
def test_hashable_equal_picklable(value):
    again = value.replace()
    assert again == value and hash(again) == hash(value) and len({value, again}) == 1
    for twin in (pickle.loads(pickle.dumps(value)), copy.deepcopy(value), copy.copy(value)):
        assert twin == value and hash(twin) == hash(value)
        if isinstance(value, Star):
            assert np.array_equal(twin.segments(), value.segments())
        else:
            assert np.array_equal(twin.segments((0, 0, 30, 30)), value.segments((0, 0, 30, 30)))
    changed = value.replace(rotation=7) if isinstance(value, Star) else value.replace(radius=11)
    assert changed != value


def test_parameter_error_names_the_parameter():
    cases = [
        (lambda: Star(n=2, radii=(1, 2)), "n"),
        (lambda: Star(n=8, radii=(1, -2)), "radii"),
        (lambda: Star(n=8, radii=(1, 2), special=5), "special"),
        (lambda: Star.preset("table9"), "preset"),
        (lambda: HexPacking(radius=-1, motif=STAR), "radius"),
        (lambda: HexPacking(radius=1, motif="star"), "motif"),
        (lambda: HexPacking(radius=1, motif=STAR, gap_motif=3), "gap_motif"),
        (lambda: HexPacking(radius=1, motif=STAR, outline_circles=1), "outline_circles"),
        (lambda: HexPacking(radius=1, motif=STAR, fill=2), "fill"),
        (lambda: packings()[0].placed_motif("small"), "which"),
    ]
    for make, param in cases:
        with pytest.raises(ParameterError) as info:
            make()
        assert info.value.param == param, (param, str(info.value))
