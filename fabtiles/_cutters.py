"""Interim: the cutter kinds' rules (to be unified with the cutters branch)."""

from __future__ import annotations

from dataclasses import dataclass

from ._errors import ParameterError


@dataclass(frozen=True)
class CutterKind:
    name: str
    opens_holes: bool
    all_layers: bool
    lightburn: bool

    def check_profile(self, profile) -> None:
        from .geometry.laser_checks import check_layers
        from .geometry.tool_opening import check_cutter

        check_cutter(profile)
        check_layers(profile)

    def check_mode(self, profile, mode) -> None:
        from .geometry.tool_opening import check_cutter_mode

        check_cutter_mode(profile, mode)

    def check_kerf(self, profile, kerf) -> None:
        if self.name == "router" and kerf != 0:
            raise ParameterError(f"kerf_mm must be 0 for router profile {profile.name!r}, got {kerf:g}: a router "
                                 "file holds the part contour and CAM offsets the tool", param="kerf_mm")
        if self.name == "waterjet" and kerf <= 0:
            raise ParameterError(f"kerf_mm must be > 0 for waterjet profile {profile.name!r} (the jet's diameter), "
                                 f"got {kerf:g}", param="kerf_mm")

    def check_format(self, profile, fmt: str) -> None:
        if fmt == "lbrn2" and not self.lightburn:
            raise ParameterError(f"a LightBurn project (.lbrn2) is for lasers; {profile.kind} profile "
                                 f"{profile.name!r} writes .dxf or .svg for its CAM", param="formats")

    def tool_name(self, profile) -> str:
        from .geometry.tool_opening import tool_name

        return tool_name(profile)


KINDS = {"laser": CutterKind("laser", False, True, True), "router": CutterKind("router", True, False, False),
         "waterjet": CutterKind("waterjet", True, False, False)}


def cutter_kind(profile) -> CutterKind:
    return KINDS[profile.kind]
