"""Inlay kits as laser files: ``<name>-lattice.<fmt>`` and ``<name>-pieces.<fmt>``, in registration.

The kit's two cut plans (:func:`fabtiles.geometry.cut_plan.plan_kit`) are written in
any laser format (DXF, SVG, LightBurn ``.lbrn2``), each file with the profile's layers:

- the lattice as a pierced tile (holes cut with the kerf into them, the outline last),
  or with ``base="pocket"`` its holes engraved as pockets on the engrave layer (for
  veneer pieces glued into a solid board) and the outline cut;
- the pieces on the outer-cut layer, each grown by half the kerf so it comes out at its
  nominal size, at its hole's place: cut from a sheet laid like the lattice's, they
  drop out where they belong. The pieces sheet has no outline of its own.

A kit is a multi-file output: :data:`KIT_FILES` names its files' suffixes, and the
build pipeline writes them as it writes any file (staged, both or neither: one format).
"""

from __future__ import annotations

KIT_FILES = (("-lattice", "lattice"), ("-pieces", "pieces"))
"""A kit's files: the suffix added to the name, and which of :class:`~fabtiles.geometry.cut_plan.KitPlans`' plans
it holds."""
