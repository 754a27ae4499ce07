"""Sweep variants (fabtiles/making/sweep.py): --vary parsing, the cross product, every bad input."""

from __future__ import annotations

import pytest

from fabtiles import ParameterError
from fabtiles.making.sweep import MAX_VARIANTS, Vary, parse_vary, variants


@pytest.mark.parametrize(
    "text, values",
    [
        ("packing.radius=8:16:5", (8, 10, 12, 14, 16)),
        ("packing.radius=16:8:3", (16, 12, 8)),
        ("tile.stroke=0.1:0.3:3", (0.1, 0.2, 0.3)),
        ("tile.stroke=1:2:3", (1.0, 1.5, 2.0)),
        ("tile.frame=3:9:1", (3,)),
        ("tile.stroke=0.8,1.2", (0.8, 1.2)),
        ("tile.outline=square,hexagon", ("square", "hexagon")),
        ("motif.preset=table3-1, table3-3", ("table3-1", "table3-3")),
        ("motif.radii=[51,70,172],[60,80,170]", ([51, 70, 172], [60, 80, 170])),
        ("packing.gap_motif.n=6,8", (6, 8)),
        ("output.fill_small_holes=true,false", (True, False)),
        ('tile.join="round"', ("round",)),
    ],
)
def test_parse_vary(text, values):
    vary = parse_vary(text)
    assert vary == Vary(text.split("=", 1)[0], values)
    assert [type(v) for v in vary.values] == [type(v) for v in values]


@pytest.mark.parametrize(
    "text, match",
    [
        ("packing.radius", r"--vary expects KEY=SPEC \(like packing\.radius=8:16:5\), got 'packing\.radius'"),
        ("tile.sise=1,2", r"--vary tile\.sise=1,2: unknown key 'sise' in \[tile\]; did you mean 'size'\?"),
        ("radius=1,2", r"'radius' is not a design key section\.key, the sections are: motif, packing"),
        ("colour.red=1,2", r"'colour\.red' is not a design key"),
        ("output.name=a,b", r"unknown key 'name' in \[output\]"),
        ("output.formats=svg,dxf", r"unknown key 'formats' in \[output\]"),
        ("packing.radius=a:b:3", r"a:b:n needs numbers a and b, got 'a' and 'b'"),
        ("packing.radius=1:inf:3", r"a and b must be finite numbers"),
        ("packing.radius=1:5:0", r"n in a:b:n must be a whole number >= 1, got 0"),
        ("packing.radius=1:5:-2", r"n in a:b:n must be a whole number >= 1, got -2"),
        ("packing.radius=1:5:2.5", r"n in a:b:n must be a whole number >= 1, got '2\.5'"),
        ("packing.radius=", r"no values; give a:b:n or a list x,y,z"),
        ("packing.radius=1,,2", r"an empty value in the list"),
        ("packing.radius=1,{bad", r"'\{bad' is not a TOML value"),
    ],
)
def test_bad_vary(text, match):
    with pytest.raises(ParameterError, match=match) as info:
        parse_vary(text)
    assert info.value.param == "vary"


def test_variants_are_the_cross_product_in_order():
    todo = variants([parse_vary("packing.radius=8:12:3"), parse_vary("tile.outline=square,hexagon")], "d")
    assert [v.name for v in todo] == [f"d-{k:03d}" for k in range(1, 7)]
    assert todo[1].values == (("packing.radius", 8), ("tile.outline", "hexagon"))
    assert todo[1].overrides() == ("packing.radius=8", 'tile.outline="hexagon"', 'output.name="d-002"')
    assert todo[5].label() == "packing.radius=12, tile.outline=hexagon"


def test_too_many_variants_need_yes():
    big = [parse_vary("packing.radius=1:2:101"), parse_vary("tile.stroke=0.1:0.2:100")]
    with pytest.raises(ParameterError, match=r"the sweep has 10,100 variants, more than 10,000; pass --yes"):
        variants(big, "d")
    todo = variants(big, "d", yes=True)
    assert len(todo) == 10_100 > MAX_VARIANTS and todo[-1].name == "d-10100" and todo[0].name == "d-00001"


def test_no_vary_or_a_key_twice():
    with pytest.raises(ParameterError, match=r"a sweep needs at least one --vary KEY=SPEC"):
        variants([], "d")
    with pytest.raises(ParameterError, match=r"--vary tile\.stroke is given twice"):
        variants([parse_vary("tile.stroke=1,2"), parse_vary("tile.stroke=3")], "d")


def test_make_jobs_needs_a_readable_design(tmp_path):
    from fabtiles import DesignError
    from fabtiles.making.sweep import make_jobs

    with pytest.raises(DesignError, match=r"cannot read design file '.*missing\.toml'"):
        make_jobs(tmp_path / "missing.toml", variants([parse_vary("tile.frame=1")], "d"), tmp_path)


def test_the_dask_extra_is_named_when_missing(monkeypatch):
    import sys

    from fabtiles import FabtilesError
    from fabtiles.making.jobs import connect

    monkeypatch.setitem(sys.modules, "distributed", None)  # as if not installed
    with pytest.raises(FabtilesError, match=r"--scheduler needs the dask extra: pip install 'fabtiles\[dask\]'"):
        connect("tcp://127.0.0.1:8786")
