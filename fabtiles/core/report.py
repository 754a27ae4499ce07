"""What an export did and what the fabrication checks found.

A :class:`Report` is the Python result object of an export; the CLI prints its
summary. A finding is a warning unless the profile is strict, in which case the
export raises :class:`~fabtiles.FabricationError` listing the findings and writes
nothing.

>>> r = Report(path="t.dxf", format="dxf")
>>> r.add("small_hole", "3 holes narrower than 1.2 mm", count=3)
>>> r.ok
False
>>> print(r.summary())
t.dxf (dxf): 1 warning
  - small_hole: 3 holes narrower than 1.2 mm
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .errors import FabricationError


def distinct(value: float, limit: float, digits: int = 3) -> str:
    """``value`` with the significant digits (``digits`` at least) that tell it from ``limit``.

    A finding's narrowest width is below its limit, and a message must show it
    (1.1996 mm is narrower than 1.2 mm; printed to three digits both read 1.2).

    >>> distinct(1.1996, 1.2), distinct(0.0229574, 0.4), distinct(1.2, 1.2)
    ('1.1996', '0.023', '1.2')
    >>> distinct(2440.0, 256.0), distinct(1200.5, 1200.0)
    ('2440', '1200.5')
    """
    whole = len(str(int(abs(value)))) if abs(value) >= 1 else 0  # a large value keeps its digits (no 2.44e+03)
    for d in range(max(digits, whole), 17):
        text = f"{value:.{d}g}"
        if value == limit or text != f"{limit:.{d}g}":
            return text
    return repr(float(value))


@dataclass(frozen=True)
class Finding:
    """One fabrication problem: a short code, a sentence, how many places, and where.

    ``locations`` are points in file coordinates (mm) where the problem is (a small
    hole's widest point, a thin bridge's or wall's narrowest point, a loose part's
    representative point); ``sizes`` the measured size at each of them, in ``unit``
    (a width in mm; a loose part's area in mm^2); ``worst`` the worst size of all
    ``count`` places (the narrowest width, the largest loose part), or None when the
    finding has no size (a height, a bed size); ``limit`` the profile's limit the sizes
    are measured against (``min_feature_mm`` for a thin bridge), or None when there is none
    (a loose part).
    """

    code: str
    message: str
    count: int = 1
    locations: tuple[tuple[float, float], ...] = ()
    sizes: tuple[float, ...] = ()
    worst: float | None = None
    unit: str = "mm"
    limit: float | None = None

    def where(self, limit: int = 3) -> str:
        """The first ``limit`` locations as text, for people.

        >>> Finding("small_hole", "", 3, ((1.0, 2.5), (3.0, 4.0), (5.0, 6.0))).where(2)
        '(1, 2.5), (3, 4) and 1 more'
        """
        shown = ", ".join(f"({x:g}, {y:g})" for x, y in self.locations[:limit])
        rest = self.count - min(limit, len(self.locations))
        return shown + (f" and {rest:,} more" if shown and rest > 0 else "")


@dataclass
class Report:
    """Result of one export: the file, measured figures and findings."""

    path: str
    format: str
    stats: dict = field(default_factory=dict)
    findings: list[Finding] = field(default_factory=list)

    def add(
        self,
        code: str,
        message: str,
        *,
        count: int = 1,
        locations=(),
        sizes=(),
        worst=None,
        unit: str = "mm",
        limit=None,
    ) -> None:
        """Record a finding (see :class:`Finding`)."""
        self.findings.append(
            Finding(
                code,
                message,
                count,
                tuple((float(p[0]), float(p[1])) for p in locations),
                tuple(map(float, sizes)),
                None if worst is None else float(worst),
                unit,
                None if limit is None else float(limit),
            )
        )

    def note(self, line: str) -> None:
        """Add a line to the summary (``stats["notes"]``): what the export did, such as holes it filled."""
        self.stats.setdefault("notes", []).append(line)

    def extended(self, *, notes=(), **stats) -> Report:
        """A copy with ``stats`` set and ``notes`` added to the summary: a model's report made once,
        never changed after its model is made.

        >>> r = Report(path="", format="", stats={"notes": ["a"]})
        >>> r.extended(notes=["b"], cutter="router").stats, r.stats
        ({'notes': ['a', 'b'], 'cutter': 'router'}, {'notes': ['a']})
        """
        out = {**self.stats, **stats}
        if notes:
            out["notes"] = [*self.stats.get("notes", ()), *notes]
        return Report(path=self.path, format=self.format, stats=out, findings=list(self.findings))

    @property
    def ok(self) -> bool:
        """True when no check found anything."""
        return not self.findings

    def raise_if_strict(self, strict: bool) -> None:
        """Turn the findings into a FabricationError when ``strict``."""
        if strict and self.findings:
            lines = "; ".join(f"{f.code}: {f.message}" for f in self.findings)
            where = f" for {self.path}" if self.path else ""  # a model's report has no file yet
            raise FabricationError(
                f"fabrication checks failed{where} (profile is strict): {lines}; "
                "fix the design or set strict = false in the profile"
            )

    def summary(self, label: str | None = None) -> str:
        """A few lines for people: the file (or ``label``: a build's model), a laser job's length and
        time, then one line per finding.

        >>> r = Report(path="t.dxf", format="dxf", stats={"job": {"line": "1.2 m of cut, 3 pierces, about 2 min"}})
        >>> print(r.summary())
        t.dxf (dxf): ok
          laser job: 1.2 m of cut, 3 pierces, about 2 min
        >>> print(r.summary("laser laser-3mm-plywood"))
        laser laser-3mm-plywood: ok
          laser job: 1.2 m of cut, 3 pierces, about 2 min
        """
        n = len(self.findings)
        head = (
            (label if label is not None else f"{self.path} ({self.format})")
            + ": "
            + ("ok" if n == 0 else f"{n} warning{'s' if n > 1 else ''}")
        )
        cutter = self.stats.get("cutter", "laser")  # a router's or a waterjet's job
        job = [f"  {cutter} job: {self.stats['job']['line']}"] if "job" in self.stats else []
        notes = [f"  {n}" for n in self.stats.get("notes", [])]
        if "material" in self.stats:
            notes.insert(0, f"  print material: {self.stats['material']['line']} (print time: ask the slicer)")
        notes += ["  " + line for line in face_class_lines(self.stats.get("face_classes", ()))]
        return "\n".join([head] + job + notes + [f"  - {f.code}: {f.message}" for f in self.findings])


def face_class_lines(classes) -> list[str]:
    """One line per face class (``FaceClasses.stats()``, with a ``colour`` where the build knows it, or
    ``filled``: the class is filled with the bands, in no colour of its own).

    >>> face_class_lines([{"letter": "A", "count": 12, "description": "8-point star", "area_mm2": 1234.5,
    ...                    "colour": "cobalt"}])
    ['face class A: 12 x 8-point star, 1,234.5 mm^2, cobalt']
    """
    out = []
    for c in classes:
        what = c.get("description") or "face"
        line = f"face class {c['letter']}: {c['count']:,} x {what}, {c['area_mm2']:,.1f} mm^2"
        if c.get("filled"):
            line += ", filled with the bands (too small to make)"
        out.append(line + (f", {c['colour']}" if c.get("colour") else ""))
    return out
