"""Reading a STEP file back (fabtiles.export.step): files OCCT cannot read or translate are refused."""

from __future__ import annotations

import pytest

from fabtiles import FabricationError
from fabtiles.export import step

HEADER = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('bad.step','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
"""


def test_a_solid_occt_cannot_translate_is_refused(tmp_path):
    path = tmp_path / "bad.step"
    # a solid whose outer shell is a point: OCCT parses the file but cannot build the solid
    path.write_text(
        HEADER + "#1=MANIFOLD_SOLID_BREP('',#2);\n#2=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n"
    )
    with pytest.raises(FabricationError, match=r"^OCCT cannot translate solid #1 of the STEP file '.*bad\.step'$"):
        step.read_step_solids(path)


@pytest.mark.parametrize("read", [step.read_step, step.read_step_solids])
def test_a_file_that_is_not_step_is_refused(tmp_path, read):
    path = tmp_path / "text.step"
    path.write_text("not a STEP file\n")
    with pytest.raises(FabricationError, match=r"^cannot read back the STEP file '.*text\.step'$"):
        read(path)
