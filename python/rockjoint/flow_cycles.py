# SPDX-License-Identifier: MIT
"""Measured flow through a joint along normal-load cycles (`rockjoint calibrate --flow`,
docs/flow.md "Transmissivity with history (issue 41)").

A CSV file in test order whose header names the columns and their units:

    normal_stress [MPa], closure [mm], transmissivity [m3]
    normal_stress [MPa], flow_rate [mL/min], pressure_drop [MPa]

``normal_stress`` (or ``stress``) is required; ``closure`` is optional; the flow is either
``transmissivity`` (m3, mm3) or a ``flow_rate`` (m3/s, L/s, L/min, mL/s, mL/min) through a stated
geometry (FlowGeometry) under a ``pressure_drop`` (or ``injection_pressure``: the pressure above
the outlet's) column or the geometry's given one; a pressure column with the geometry's given rate
is an injection test at a stated rate. The transmissivity of a rate (q = -(T/μ) ∇p per unit
width, docs/flow.md):

* radial flow from a central borehole of radius r_i to the rim r_o of a core (the laboratory's
  usual set-up; Witherspoon, Wang, Iwai & Gale 1980, Water Resour. Res. 16(6), 1016-1024):
  Q = 2π T Δp / (μ ln(r_o/r_i)), so T = μ Q ln(r_o/r_i) / (2π Δp);
* linear flow along a length L across a width W: Q = W T Δp / (μ L), so T = μ Q L / (W Δp).

Lines starting with '#' and blank lines are skipped; every mistake names the file and line. SI
inside.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .calibration import read_rows
from .cycle_calibration import branch_labels
from .units import DIMENSIONS

#: column -> (accepted names, dimension of its unit)
COLUMNS = {"normal_stress": (("normal_stress", "stress"), "stress"),
           "closure": (("closure",), "length"),
           "transmissivity": (("transmissivity",), "transmissivity"),
           "flow_rate": (("flow_rate", "rate"), "flow_rate"),
           "pressure_drop": (("pressure_drop", "injection_pressure"), "stress")}
_HEADER = re.compile(r"^\s*([A-Za-z_ ]+?)\s*\[([^\]]*)\]\s*$")
#: one millilitre per minute [m³/s] (the CLI's --rate)
ML_PER_MIN = DIMENSIONS["flow_rate"]["mL/min"]
#: water at 20 °C [Pa s] (fem.water.joint_flow.Fluid's default, CRC Handbook)
WATER_VISCOSITY = 1.002e-3


@dataclass(frozen=True)
class FlowGeometry:
    """How a measured flow rate becomes a transmissivity: `kind` 'radial' (inner_radius r_i,
    outer_radius r_o [m]) or 'linear' (width W, length L [m]); `pressure_drop` Δp [Pa] and
    `flow_rate` Q [m³/s] where the file has no such column; fluid `viscosity` μ [Pa s]."""

    kind: str = "radial"
    inner_radius: Optional[float] = None
    outer_radius: Optional[float] = None
    width: Optional[float] = None
    length: Optional[float] = None
    pressure_drop: Optional[float] = None
    flow_rate: Optional[float] = None
    viscosity: float = WATER_VISCOSITY

    def __post_init__(self):
        needed = {"radial": ("inner_radius", "outer_radius"), "linear": ("width", "length")}
        if self.kind not in needed:
            raise ValueError(f"flow geometry: kind = {self.kind!r}; expected 'radial' or 'linear'")
        for name in needed[self.kind] + ("viscosity",):
            v = getattr(self, name)
            if v is None or not (math.isfinite(v) and v > 0):
                raise ValueError(f"flow geometry ({self.kind}): {name} = {v!r} must be given, finite and > 0")
        for name in ("pressure_drop", "flow_rate"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise ValueError(f"flow geometry: {name} = {v!r} must be finite and > 0")
        if self.kind == "radial" and not self.outer_radius > self.inner_radius:
            raise ValueError(f"flow geometry (radial): outer_radius {self.outer_radius} m must exceed "
                             f"inner_radius {self.inner_radius} m")

    def transmissivity(self, flow_rate, pressure_drop) -> np.ndarray:
        """T [m³] of flow rates Q [m³/s] under pressure drops Δp [Pa] (module docstring)."""
        shape = (math.log(self.outer_radius / self.inner_radius) / (2 * math.pi) if self.kind == "radial"
                 else self.length / self.width)
        return self.viscosity * np.asarray(flow_rate, float) * shape / np.asarray(pressure_drop, float)


@dataclass
class FlowCycles:
    """Measured flow cycles in SI, in test order: stress [Pa], closure [m] (or None) and
    transmissivity [m³] per point, the file's line of each point and the file's name."""

    normal_stress: np.ndarray
    transmissivity: np.ndarray
    closure: Optional[np.ndarray] = None
    lines: Optional[np.ndarray] = None
    source: str = "<array>"

    def __post_init__(self):
        self.normal_stress = np.asarray(self.normal_stress, dtype=float)
        self.transmissivity = np.asarray(self.transmissivity, dtype=float)
        if self.closure is not None:
            self.closure = np.asarray(self.closure, dtype=float)
        if self.lines is None:
            self.lines = np.arange(1, self.normal_stress.size + 1)
        checks = (("normal stress", self.normal_stress, lambda v: v >= 0, ">= 0 (compression +)"),
                  ("transmissivity", self.transmissivity, lambda v: v > 0, "> 0"))
        if self.closure is not None:
            checks += (("closure", self.closure, lambda v: True, "finite"),)
        for name, v, ok, words in checks:
            if v.shape != self.normal_stress.shape or v.ndim != 1:
                raise ValueError(f"{self.source}: {name} must be a 1-D array with one value per point")
            bad = np.flatnonzero(~(np.isfinite(v) & ok(v)))
            if bad.size:
                raise ValueError(f"{self.source}: line {int(self.lines[bad[0]])}: {name} "
                                 f"{v[bad[0]]:.6g} must be finite and {words}")
        labels = self.branches()
        for b in ("loading", "unloading"):
            if np.count_nonzero(labels == b) < 3:
                raise ValueError(f"{self.source}: {np.count_nonzero(labels == b)} point(s) on {b} "
                                 "branches; flow cycles need at least 3 on loading and 3 on unloading")

    def branches(self) -> np.ndarray:
        """'loading', 'unloading' or 'reloading' per point (cycle_calibration.branch_labels)."""
        return branch_labels(self.normal_stress)


def _columns(path: str, line: int, header) -> dict:
    """{column: (index, SI factor)} of a header like 'normal_stress [MPa], closure [mm], ...'."""
    out = {}
    for j, cell in enumerate(header):
        m = _HEADER.match(cell)
        name = m.group(1).strip().lower().replace(" ", "_") if m else None
        for column, (names, dimension) in COLUMNS.items():
            if name in names:
                units = {u.lower(): f for u, f in DIMENSIONS[dimension].items()}
                factor = units.get(m.group(2).strip().lower())
                if factor is None:
                    raise ValueError(f"{path}: line {line}: column '{cell.strip()}' has unit "
                                     f"'{m.group(2)}'; use one of {', '.join(DIMENSIONS[dimension])}")
                out[column] = (j, factor)
    return out


def read_flow_cycles(path, geometry: Optional[FlowGeometry] = None) -> FlowCycles:
    """FlowCycles from a CSV file (module docstring); `geometry` turns a flow rate into T."""
    path = str(path)
    (line, header), *rows = read_rows(path, "the flow cycles")
    cols = _columns(path, line, header)
    if "normal_stress" not in cols:
        raise ValueError(f"{path}: line {line}: no normal stress column; the header needs e.g. "
                         f"'normal_stress [MPa], transmissivity [m3]' (got {', '.join(header)})")
    if ("transmissivity" in cols) == ("flow_rate" in cols or "pressure_drop" in cols):
        raise ValueError(f"{path}: line {line}: give either a 'transmissivity [m3]' column or a flow "
                         f"rate and a pressure drop (columns or the geometry's), not both and not "
                         f"neither (got {', '.join(header)})")
    data = {c: [] for c in cols}
    for k, r in rows:
        for c, (j, factor) in cols.items():
            cell = r[j].strip() if j < len(r) else ""
            try:
                data[c].append(float(cell) * factor)
            except ValueError:
                raise ValueError(f"{path}: line {k}: {c} '{cell}' is not a number") from None
    lines = np.array([k for k, _ in rows])
    if "transmissivity" in cols:
        t = np.array(data["transmissivity"])
    else:
        if geometry is None:
            raise ValueError(f"{path}: a flow rate or pressure needs the test's geometry (radial: inner "
                             "and outer radius; linear: width and length) to give a transmissivity")
        rate = np.array(data["flow_rate"]) if "flow_rate" in cols else geometry.flow_rate
        drop = np.array(data["pressure_drop"]) if "pressure_drop" in cols else geometry.pressure_drop
        for name, v in (("flow_rate", rate), ("pressure_drop", drop)):
            if v is None:
                raise ValueError(f"{path}: no {name} column and none given with the geometry")
            bad = np.flatnonzero(~(np.asarray(v) > 0)) if np.ndim(v) else []
            if len(bad):
                raise ValueError(f"{path}: line {lines[bad[0]]}: {name} must be > 0")
        t = geometry.transmissivity(rate, drop) * np.ones(lines.size)
    closure = np.array(data["closure"]) if "closure" in cols else None
    return FlowCycles(np.array(data["normal_stress"]), t, closure, lines, path)
