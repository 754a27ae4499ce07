"""The build: a design's models made once, each format's files written or refused on its own, for every front end.

- :mod:`.models`: :class:`BuildOptions` (the profiles, loaded once, and the options)
  and :class:`Models` (the cut plan and the print model of one tile or sheet);
- :mod:`.pipeline`: :func:`build_design` (files into a folder), :func:`build_bytes`
  (one format as bytes, the web app's downloads), :func:`export_tile` and
  :func:`export_region` (the API's one-file exports);
- :mod:`.views`: the pictures' and the 3D view's geometry from the same models;
- :mod:`.staging`: the files made, moved into place together; :mod:`.outcome`: batch and sweep results.
"""

from .models import BuildOptions, Models
from .outcome import Outcome, outcome_of, run_job
from .pipeline import (
    PREVIEW_SUFFIX,
    SHEET_SUFFIX,
    BuildResult,
    Download,
    Refused,
    build_bytes,
    build_design,
    check_format_limits,
    export_region,
    export_tile,
    layout_tile_sheet,
    prepare_tile,
    sheet_formats,
    write_files,
)
from .staging import STAGING_PREFIX, StagingFolder, remove_stale_staging
from .views import VIEW_SEGMENTS, inlay_kit_of, made_region, print_view

__all__ = [
    "PREVIEW_SUFFIX",
    "SHEET_SUFFIX",
    "STAGING_PREFIX",
    "VIEW_SEGMENTS",
    "BuildOptions",
    "BuildResult",
    "Download",
    "Models",
    "Outcome",
    "Refused",
    "StagingFolder",
    "build_bytes",
    "build_design",
    "check_format_limits",
    "export_region",
    "export_tile",
    "inlay_kit_of",
    "layout_tile_sheet",
    "made_region",
    "outcome_of",
    "prepare_tile",
    "print_view",
    "remove_stale_staging",
    "run_job",
    "sheet_formats",
    "write_files",
]
