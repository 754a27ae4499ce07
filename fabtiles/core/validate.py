"""Small argument checkers shared by every layer.

Each raises :class:`~fabtiles.ParameterError` with a message that names the
parameter, the value given and the allowed range, so the caller knows how to
fix the call; the error's ``param`` is the parameter's name.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Sequence

from .errors import ParameterError


def check_int(name: str, value, *, low: int | None = None, high: int | None = None) -> int:
    """Return ``value`` as an int, checking it is an integer within ``[low, high]``.

    >>> check_int("n", 8, low=3)
    8
    >>> check_int("n", 2, low=3)
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: n must be an integer >= 3, got 2
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        if (
            isinstance(value, numbers.Real)
            and not isinstance(value, bool)
            and math.isfinite(value)
            and float(value).is_integer()
        ):
            value = math.trunc(value)  # int(value), for any Real
        else:
            raise ParameterError(f"{name} must be an integer{_range_text(low, high)}, got {value!r}", param=_base(name))
    value = int(value)
    if (low is not None and value < low) or (high is not None and value > high):
        raise ParameterError(f"{name} must be an integer{_range_text(low, high)}, got {value}", param=_base(name))
    return value


def check_float(
    name: str,
    value,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
) -> float:
    """Return ``value`` as a finite float within the given bounds.

    >>> check_float("stroke", 1, low=0, low_open=True)
    1.0
    >>> check_float("stroke", float("nan"))
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: stroke must be a finite number, got nan
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(
            f"{name} must be a finite number{_range_text(low, high, low_open, high_open)}, got {value!r}",
            param=_base(name),
        )
    value = float(value)
    if not math.isfinite(value):
        raise ParameterError(
            f"{name} must be a finite number{_range_text(low, high, low_open, high_open)}, got {value}",
            param=_base(name),
        )
    bad_low = low is not None and (value <= low if low_open else value < low)
    bad_high = high is not None and (value >= high if high_open else value > high)
    if bad_low or bad_high:
        raise ParameterError(
            f"{name} must be a finite number{_range_text(low, high, low_open, high_open)}, got {_fmt(value)}",
            param=_base(name),
        )
    return value


def check_choice(name: str, value, choices: Sequence[str]) -> str:
    """Return ``value`` if it is one of ``choices``.

    >>> check_choice("join", "zigzag", ("miter", "round", "bevel"))
    Traceback (most recent call last):
    ...
    fabtiles.core.errors.ParameterError: 'zigzag' is not a valid join, must be one of: miter, round, bevel
    """
    if not isinstance(value, str) or value not in choices:
        raise ParameterError(
            f"{value!r} is not a valid {name}, must be one of: {', '.join(choices)}", param=_base(name)
        )
    return value


def check_float_seq(
    name: str,
    values,
    *,
    min_len: int,
    max_len: int,
    low: float | None = None,
    low_open: bool = False,
) -> tuple[float, ...]:
    """Return ``values`` as a tuple of finite floats, each checked like :func:`check_float`.

    >>> check_float_seq("radii", [1, 2], min_len=2, max_len=4, low=0, low_open=True)
    (1.0, 2.0)
    """
    if isinstance(values, (str, bytes)) or not isinstance(values, Iterable):
        raise ParameterError(
            f"{name} must be a sequence of {min_len} to {max_len} numbers, got {values!r}", param=_base(name)
        )
    values = list(values)
    if not min_len <= len(values) <= max_len:
        raise ParameterError(
            f"{name} must hold {min_len} to {max_len} numbers, got {len(values)}: {values!r}",
            param=_base(name),
        )
    return tuple(check_float(f"{name}[{k}]", v, low=low, low_open=low_open) for k, v in enumerate(values))


def _base(name: str) -> str:
    """The parameter a checked name belongs to: ``radii[1]`` -> ``radii``."""
    return name.split("[", 1)[0]


def _fmt(x: float) -> str:
    return f"{x:g}"


def _range_text(low, high, low_open=False, high_open=False) -> str:
    parts = []
    if low is not None:
        parts.append(f"{'>' if low_open else '>='} {_fmt(low)}")
    if high is not None:
        parts.append(f"{'<' if high_open else '<='} {_fmt(high)}")
    return (" " + " and ".join(parts)) if parts else ""
