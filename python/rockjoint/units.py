# SPDX-License-Identifier: MIT
"""Units of every file, scene and report rockjoint reads or writes: one table per dimension,
{unit: SI per unit}. Lengths are the C++ table (topography/units.cpp, through the bindings), so
the topography file parser and the Python layer accept the same length units; the law
parameters' units (rockjoint.law_registry.UNITS: mm, MPa, GPa, MPa/mm, 1/mm²) and the scene
files' (rockjoint.scenes.units) are entries of these tables.
"""
from __future__ import annotations

import math

from ._rockjoint.topography import length_units

#: dimension -> {unit: SI per unit}
DIMENSIONS = {
    "stress": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "length": dict(length_units()),
    "angle": {"deg": math.pi / 180.0, "°": math.pi / 180.0, "rad": 1.0},
    "stiffness": {"Pa/m": 1.0, "MPa/m": 1e6, "GPa/m": 1e9, "MPa/mm": 1e9},   # k_n, k_s
    "density": {"kg/m3": 1.0, "kg/m³": 1.0, "t/m3": 1e3},
    "per_area": {"1/m2": 1.0, "1/mm2": 1e6, "1/mm²": 1e6},                  # summit density η
    # intrinsic permeability k of rock (1 darcy = 9.869233e-13 m², by its definition)
    "permeability": {"m2": 1.0, "m²": 1.0, "D": 9.869233e-13, "mD": 9.869233e-16},
    "fraction": {"%": 1e-2, "-": 1.0},
    # a joint's transmissivity T (q = -(T/μ) ∇p per unit width) and a laboratory flow rate
    "transmissivity": {"m3": 1.0, "m³": 1.0, "mm3": 1e-9, "mm³": 1e-9},
    "flow_rate": {"m3/s": 1.0, "m³/s": 1.0, "L/s": 1e-3, "L/min": 1e-3 / 60, "mL/s": 1e-6, "mL/min": 1e-6 / 60},
    "number": {"-": 1.0},
}
#: the units of law parameters in files and reports, with their dimension
LAW_UNIT_DIMENSION = {"-": "number", "mm": "length", "MPa": "stress", "GPa": "stress",
                      "MPa/mm": "stiffness", "1/mm²": "per_area"}
