"""Quantities with their units, as a scene file states them ("30 MPa", "0.5 mm", "60 deg"), in SI.

A scene states a unit for every dimensional value so that nothing is read in the wrong one; a bare
number is accepted only for dimensionless quantities (Poisson's ratio, ratios, counts). Each
dimension lists the units it accepts and their SI factor; the law parameters' own units come from
rockjoint.law_registry.UNITS (the one copy of the mm/MPa/GPa factors), mapped to a dimension here.
"""
from __future__ import annotations

import math
import re

from ..law_registry import UNITS as LAW_UNITS

#: dimension -> {unit: SI per unit}
DIMENSIONS = {
    "stress": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "km": 1e3},
    "angle": {"deg": math.pi / 180.0, "°": math.pi / 180.0, "rad": 1.0},
    "stiffness": {"Pa/m": 1.0, "MPa/m": 1e6, "GPa/m": 1e9, "MPa/mm": 1e9},   # k_n, k_s
    "density": {"kg/m3": 1.0, "kg/m³": 1.0, "t/m3": 1e3},
    "per_area": {"1/m2": 1.0, "1/mm2": 1e6, "1/mm²": 1e6},                  # summit density η
    "fraction": {"%": 1e-2, "-": 1.0},
    "number": {"-": 1.0},
}
#: the dimension of each law-registry unit (a law parameter's Quantity.unit)
LAW_UNIT_DIMENSION = {"-": "number", "mm": "length", "MPa": "stress", "GPa": "stress",
                      "MPa/mm": "stiffness", "1/mm²": "per_area"}
assert set(LAW_UNIT_DIMENSION) == set(LAW_UNITS), "a law unit has no dimension in scenes.units"

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
