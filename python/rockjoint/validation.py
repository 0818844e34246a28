# SPDX-License-Identifier: MIT
"""Checks of scalar inputs with errors that name the parameter, its value and the valid range."""
from __future__ import annotations

import math


def positive_number(name: str, value, allow_zero: bool = False, unit: str = "") -> float:
    """float(value), checked finite and > 0 (>= 0 with allow_zero); `name` and `unit` (e.g.
    "kg/m³") go into the error message."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number{f' [{unit}]' if unit else ''}, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} = {value!r}{f' {unit}' if unit else ''} is invalid; it must be finite and {bound}")
    return v
