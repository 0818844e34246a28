# SPDX-License-Identifier: MIT
"""Quantities with their units, as a scene file states them ("30 MPa", "0.5 mm", "60 deg"), in SI.

A scene states a unit for every dimensional value so that nothing is read in the wrong one; a bare
number is accepted only for dimensionless quantities (Poisson's ratio, ratios, counts). The units
each dimension accepts and their SI factors are rockjoint.units.DIMENSIONS (the one table; its
lengths are the C++ topography parser's own).
"""
from __future__ import annotations

import math
import re

from ..units import DIMENSIONS, LAW_UNIT_DIMENSION  # noqa: F401  (the one table; re-exported)

_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*?)?\s*$")


def parse_quantity(value, dimension: str) -> float:
    """`value` ("30 MPa", 0.25, "5 %") in SI for `dimension`; ValueError saying what is wrong."""
    units = DIMENSIONS[dimension]
    if isinstance(value, bool):
        raise ValueError(f"expected a {dimension} value, got {value!r}")
    if isinstance(value, (int, float)):
        if dimension in ("number", "fraction"):
            number = float(value)
        else:
            raise ValueError(f"{value!r} has no unit; a {dimension} needs one of "
                             f"{', '.join(units)} (e.g. '{value} {next(iter(units))}')")
    elif isinstance(value, str):
        match = _QUANTITY.match(value)
        if not match:
            raise ValueError(f"{value!r} is not a number with a unit (e.g. '30 MPa')")
        number, unit = float(match.group(1)), match.group(2) or "-"
        if unit not in units:
            raise ValueError(f"{value!r}: unit {unit!r} is not a {dimension} unit; use one of "
                             f"{', '.join(u for u in units if u != '-') or 'none'}")
        number *= units[unit]
    else:
        raise ValueError(f"expected a {dimension} value, got {type(value).__name__} {value!r}")
    if not math.isfinite(number):
        raise ValueError(f"{value!r} is not finite")
    return number


def in_unit_of(value, si: float, dimension: str) -> str:
    """`si` written in the unit `value` was given in ("90 deg" for π/2 when the user wrote
    "95 deg"): a limit in a message reads in the user's terms. SI for a value whose unit is not
    one of the dimension's (parse_quantity refuses those anyway)."""
    units = DIMENSIONS[dimension]
    match = _QUANTITY.match(value) if isinstance(value, str) else None
    unit = (match.group(2) or "-") if match else "-"
    if unit not in units:
        return f"{si:g} (SI)"
    number = f"{si / units[unit]:g}"
    return number if unit == "-" else f"{number} {unit}"
