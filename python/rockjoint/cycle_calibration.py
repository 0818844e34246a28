# SPDX-License-Identifier: MIT
"""Calibration of a hysteretic closure law to measured load cycles (docs/hysteresis.md §calibration).

A laboratory closure test loads and unloads a joint one or more times: the stress path σ_i (the
controlled variable, in test order) and the closure Δ_i (the measured one). The model is a
NormalHysteresis: a virgin law (any calibratable law of the registry) with unloading/reloading
branches, permanent closure r Δ_m and branch exponent m (H1-H2). All of it is fitted at once:
residuals r_i = Δ_model(σ_0..σ_i; p) - Δ_i along the path (NormalHysteresis.closure_path), by
the same Levenberg-Marquardt as calibration.py (GSL through fit_curve). The virgin law's positive
parameters are fitted as logarithms, r as a logit (0 < r < 1) and m - 1 as a logarithm (m > 1), so
the search space has no boundary; standard uncertainties are carried back to first order
(σ_p = p σ_ln p, σ_r = r (1 - r) σ_logit, σ_m = (m - 1) σ_ln(m-1)).

The seating offset. A laboratory cycle starts at a seating load σ_0 > 0 where the gauges are
zeroed: the measured closure is counted from there, while the law's closure is counted from the
virgin joint at zero stress, Δ(σ_0) > 0 already. The model of the data is therefore
Δ_i = Δ_model(σ_0..σ_i; p) - Δ_0 (as calibration.py's closure offset), with Δ_0, the law's closure
at the data's zero, fitted beside the other parameters (default; fit_offset=False fixes Δ_0 = 0,
for data whose first point is the unloaded virgin joint). Forcing Δ_0 = 0 on seated data makes
the virgin law itself absorb the missing closure (too soft at low stress) and leaves r, the
closure kept at zero stress, to that distortion. Δ_0 is a fitted parameter with its own
uncertainty; r, m and the permanent closure r Δ_m are in the law's frame (from the virgin joint).

The report gives the rms residual of each branch (virgin loading, unloading, reloading), per
cycle the measured and fitted closure at the lowest stress of its unloading (what the data show),
and the parameters with their uncertainties. A parameter whose standard uncertainty exceeds its
value (or is not finite) is reported as not identifiable from these data instead of as a value:
a cycle that ends at a seating load leaves r Δ_m, the closure at zero stress, to an extrapolation
that m can mimic (Δ ∝ σ^(1/m) falls steeply near σ = 0), so the fit may drive r to 0 with an
uncertainty larger than r while the data keep a large closure at their lowest stress.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from ._rockjoint import calibration as _cpp_calibration
from ._rockjoint.constitutive import NormalHysteresis
from .law_registry import HISTORY_PARAMETERS
from .calibration import (CLOSURE_OFFSET, FittedParameter, calibration_spec, check_points, closure_of,
                          read_columns)

__all__ = ["LoadCycles", "read_load_cycles", "calibrate_cycles", "CycleCalibration", "BRANCHES",
           "UnloadingEnd", "identifiable", "branch_labels"]

#: branch labels of the points of a path
BRANCHES = ("loading", "unloading", "reloading")


@dataclass
class LoadCycles:
    """Measured load cycles in SI, in test order: stress [Pa] and closure [m] per point."""
    normal_stress: np.ndarray
    closure: np.ndarray
    lines: Optional[np.ndarray] = None
    source: str = "<array>"

    def __post_init__(self) -> None:
        self.normal_stress = np.asarray(self.normal_stress, dtype=float)
        self.closure = np.asarray(self.closure, dtype=float)
        if self.lines is None:
            self.lines = np.arange(1, self.closure.size + 1)
        check_points(self, "load cycles are compressive")
        labels = self.branches()
        for b in ("loading", "unloading"):
            if np.count_nonzero(labels == b) < 3:
                raise ValueError(f"{self.source}: {np.count_nonzero(labels == b)} point(s) on "
                                 f"{b} branches; load cycles need at least 3 on loading and 3 on "
                                 "unloading (is this a single loading curve? use calibrate)")

    def branches(self) -> np.ndarray:
        """Label of each point (branch_labels of its stress path)."""
        return branch_labels(self.normal_stress)


def branch_labels(stress) -> np.ndarray:
    """Label of each point of a stress path in test order: 'loading' (virgin: the stress reaches
    a new maximum), 'unloading' (stress falling) or 'reloading' (rising below the earlier maximum)."""
    s = np.asarray(stress, dtype=float)
    out = np.empty(s.size, dtype=object)
    top = -math.inf
    for i, v in enumerate(s):
        if v >= top:
            out[i], top = "loading", v
        else:
            out[i] = "unloading" if i > 0 and v < s[i - 1] else "reloading"
    return out


def read_load_cycles(path) -> LoadCycles:
    """Load cycles from a CSV file in test order: the header names the columns and units, as for
    read_closure_curve (``normal_stress [MPa], closure [mm]``); rows need not be monotone."""
    stress, closure, _, lines, source = read_columns(path)
    return LoadCycles(stress, closure, lines, source)


def identifiable(p: FittedParameter, closure_range: float = math.inf) -> bool:
    """True if the data determine ``p``: a finite standard uncertainty no larger than the value;
    for the seating offset Δ_0, a location that may be zero, no larger than a tenth of the
    measured ``closure_range`` [m]."""
    if not math.isfinite(p.standard_error):
        return False
    if p.name == CLOSURE_OFFSET.name:
        return p.standard_error <= 0.1 * closure_range
    return p.standard_error <= abs(p.value)


@dataclass(frozen=True)
class UnloadingEnd:
    """The lowest stress of one unloading run (one cycle) and the closure there [SI]."""
    cycle: int               # 1-based, in test order
    line: int                # line of the point in the data file (1-based point index for arrays)
    peak_stress: float       # largest stress reached before this unloading [Pa]
    normal_stress: float     # lowest stress of the unloading [Pa]
    measured_closure: float  # [m]
    fitted_closure: float    # [m]


@dataclass
class CycleCalibration:
    """Result of calibrate_cycles: the fitted NormalHysteresis and the statistics of the fit."""
    law_name: str
    law: NormalHysteresis
    parameters: List[FittedParameter]
    cycles: LoadCycles
    residuals: np.ndarray                   # model - data closure [m]
    given: Dict[str, object] = field(default_factory=dict)
    fit: object = None
    closure_offset: float = 0.0             # Δ_0: the law's closure at the data's zero [m]

    def branch_rms(self) -> Dict[str, float]:
        """rms closure residual [m] per branch (those present)."""
        labels = self.cycles.branches()
        return {b: float(np.sqrt(np.mean(self.residuals[labels == b] ** 2)))
                for b in BRANCHES if np.any(labels == b)}

    def permanent_closures(self) -> np.ndarray:
        """Fitted permanent closure r Δ_m [m] at the end of each unloading (the lowest stress of
        each unloading run), in the law's frame (from the virgin joint at zero stress)."""
        labels = self.cycles.branches()
        predicted = self.predicted_closure() + self.closure_offset
        out, dm = [], 0.0
        for i, b in enumerate(labels):
            dm = max(dm, predicted[i])
            ends = b == "unloading" and (i + 1 == labels.size or labels[i + 1] != "unloading")
            if ends:
                out.append(self.law.permanent_closure(dm))
        return np.array(out)

    def unloading_ends(self) -> List[UnloadingEnd]:
        """Per cycle, the measured and fitted closure at the lowest stress of its unloading: the
        closure the data keep (the permanent closure proper, at zero stress, is an
        extrapolation unless the unloading reaches zero)."""
        c, labels, predicted = self.cycles, self.cycles.branches(), self.predicted_closure()
        out, top = [], 0.0
        for i, b in enumerate(labels):
            top = max(top, float(c.normal_stress[i]))
            if b == "unloading" and (i + 1 == labels.size or labels[i + 1] != "unloading"):
                out.append(UnloadingEnd(len(out) + 1, int(c.lines[i]), top,
                                        float(c.normal_stress[i]), float(c.closure[i]),
                                        float(predicted[i])))
        return out

    def not_identifiable(self) -> List[str]:
        """Names of the parameters these data do not determine (see ``identifiable``)."""
        return [p.name for p in self.parameters if not identifiable(p, self.closure_range)]

    @property
    def closure_range(self) -> float:
        """The measured closure's range [m]."""
        return float(np.ptp(self.cycles.closure))

    def predicted_closure(self) -> np.ndarray:
        """The fitted closure at each point on the data's datum [m] (the law's path - Δ_0)."""
        return np.asarray(self.law.closure_path(self.cycles.normal_stress), dtype=float) - self.closure_offset

    def parameter(self, name: str) -> FittedParameter:
        """The fitted parameter `name` (KeyError if the law has none of that name)."""
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def report(self) -> str:
        """The calibration in words: the data, the given and fitted parameters with their uncertainties."""
        c = self.cycles
        top = float(np.max(c.closure))
        lines = [f"cycle calibration of '{self.law_name}' with unloading branches to {c.source}",
                 f"  {c.closure.size} points, normal stress up to {np.max(c.normal_stress) * 1e-6:.4g} "
                 f"MPa, closure up to {top * 1e3:.4g} mm"]
        for k, v in self.given.items():
            lines.append(f"  given: {k} = {v}")
        lines.append("  fitted parameters (± standard uncertainty from the covariance scaled by the "
                     "residual variance):")
        for p in self.parameters:
            if identifiable(p, self.closure_range):
                lines.append(f"    {p}")
            else:
                unit = "" if p.unit == "-" else f" {p.unit}"
                bound = ("a tenth of the measured closure" if p.name == CLOSURE_OFFSET.name
                         else "the value")
                lines.append(f"    {p.symbol:>4}   not identifiable from these data (the fit gives "
                             f"{p.value / p.scale:.3g} ± {p.standard_error / p.scale:.2g}{unit}: "
                             f"the uncertainty exceeds {bound})")
        for b, rms in self.branch_rms().items():
            lines.append(f"  {b:9s} rms {rms * 1e6:.4g} µm = {rms / top:.2%} of the maximum closure")
        ends = self.unloading_ends()
        lines.append("  closure at the lowest stress of each unloading (measured, fitted):")
        for e in ends:
            lines.append(f"    cycle {e.cycle}: {e.peak_stress * 1e-6:.4g} -> "
                         f"{e.normal_stress * 1e-6:.4g} MPa (line {e.line}): "
                         f"{e.measured_closure * 1e3:.4g} mm, {e.fitted_closure * 1e3:.4g} mm")
        r = self.parameter(HISTORY_PARAMETERS[0].name)
        lowest = min(e.normal_stress for e in ends)
        if not identifiable(r, self.closure_range):
            lines.append("  permanent closure (at zero stress): not identifiable from these data: "
                         f"the unloading stops at {lowest * 1e-6:.4g} MPa and the closure kept "
                         "there does not fix r (the branch exponent m reproduces it over r's whole "
                         "uncertainty); unload closer to zero stress to measure it")
        else:
            where = ("" if lowest == 0.0 else
                     f", extrapolated below the lowest unloaded stress {lowest * 1e-6:.4g} MPa")
            frame = ("" if self.closure_offset == 0.0 else
                     f"; from the virgin joint, Δ_0 = {self.closure_offset * 1e3:.4g} mm below the data's zero")
            lines.append("  permanent closure after each unloading (at zero stress" + where + frame + "): "
                         + ", ".join(f"{p * 1e3:.4g} mm" for p in self.permanent_closures())
                         + f" (r = {r.value:.3g} of the largest closure)")
        return "\n".join(lines)


def _logit(r: float) -> float:
    return math.log(r / (1.0 - r))


def calibrate_cycles(cycles: LoadCycles, law: str, *, composite_modulus: Optional[float] = None,
                     summit_radius: Optional[float] = None, maximum_iterations: int = 500,
                     initial: Optional[List[float]] = None, fit_offset: bool = True) -> CycleCalibration:
    """Fit a virgin ``law`` (a calibratable law of the registry) with unloading branches and the
    seating offset Δ_0 (``fit_offset``) to ``cycles``; see the module docstring. ``initial``:
    starting values in SI, the law's unknowns, then Δ_0 (with ``fit_offset``), r and m (default:
    the law's own guess on the virgin points, Δ_0 the guessed law's closure at the first point
    less the measured one, r from the lowest unloaded closure, m = 2)."""
    spec, given = calibration_spec(law, composite_modulus, summit_radius, "calibrate_cycles")
    npos = len(spec.unknowns)
    nfit = npos + (1 if fit_offset else 0)          # the law's unknowns, then Δ_0
    labels = cycles.branches()
    virgin = labels == "loading"
    if initial is None:
        s_v, d_v = cycles.normal_stress[virgin], cycles.closure[virgin]
        shift = 0.0
        if fit_offset and s_v[0] > 0 and s_v.size > 1:
            # the law's guess needs closure from its datum: shift the points by the secant of the
            # first two extrapolated to σ = 0 (an underestimate of Δ_0 on a concave virgin curve;
            # the fit corrects it). Unshifted, a seated cycle can start the fit far off (K_ni
            # ~5e12 Pa/m on the laboratory-looking test) and diverge.
            slope = (d_v[1] - d_v[0]) / (s_v[1] - s_v[0])
            shift = max(s_v[0] * slope - d_v[0], 0.0)
        start = list(spec.initial_guess(s_v, d_v + shift, given, spec.build, False, closure_of))[:npos]
        if fit_offset:
            seated = closure_of(spec.build(start, given), cycles.normal_stress[:1])[0]
            start.append(max(float(seated - cycles.closure[0]), 0.0))
        lowest = float(np.min(cycles.closure[labels == "unloading"]))
        r0 = min(max(lowest / max(float(np.max(cycles.closure)), 1e-300), 0.05), 0.9)
        start += [r0, 2.0]
    else:
        start = list(initial)
    if len(start) != nfit + 2:
        raise ValueError(f"calibrate_cycles: {len(start)} initial values for {nfit + 2} parameters")
    if not (0.0 < start[nfit] < 1.0 and start[nfit + 1] > 1.0):
        raise ValueError(f"calibrate_cycles: initial r = {start[nfit]} must be in (0, 1) and "
                         f"m = {start[nfit + 1]} > 1")
    scale = float(np.max(np.abs(cycles.closure))) or 1.0

    # Fitted vector q: ln p for the law's parameters, Δ_0/scale (any sign while fitting), logit r,
    # ln(m - 1).
    def unpack(q):
        values = [math.exp(x) for x in q[:npos]]
        offset = q[npos] * scale if fit_offset else 0.0
        r = 1.0 / (1.0 + math.exp(-q[nfit]))
        return values, offset, r, 1.0 + math.exp(q[nfit + 1])

    def build(q):
        values, _, r, m = unpack(q)
        return NormalHysteresis(spec.build(values, given), r, m)

    def model(q):
        try:
            return (np.asarray(build(q).closure_path(cycles.normal_stress)) - unpack(q)[1]) / scale
        except (ValueError, OverflowError):  # a trial beyond the admissible: steer the fit back
            return np.full(cycles.closure.size, 1e3)

    q0 = ([math.log(v) for v in start[:npos]] + ([start[npos] / scale] if fit_offset else [])
          + [_logit(start[nfit]), math.log(start[nfit + 1] - 1.0)])
    result = _cpp_calibration.fit_curve(model, cycles.closure / scale, np.array(q0), None,
                                        maximum_iterations=maximum_iterations)
    q, se = result.parameters, result.standard_errors
    values, offset, r, m = unpack(q)
    params = [FittedParameter(u.name, u.symbol, values[j], values[j] * se[j], u.unit, u.scale)
              for j, u in enumerate(spec.unknowns)]
    if fit_offset:
        o = CLOSURE_OFFSET
        params.append(FittedParameter(o.name, o.symbol, offset, se[npos] * scale, o.unit, o.scale))
    # r = logistic(q), m = 1 + exp(q): their standard errors by the chain rule
    permanent, exponent = HISTORY_PARAMETERS   # the history's record (NormalHysteresis's own specs)
    for quantity, value, error in ((permanent, r, r * (1 - r) * se[nfit]), (exponent, m, (m - 1) * se[nfit + 1])):
        params.append(FittedParameter(quantity.name, quantity.symbol, value, error, quantity.unit, quantity.scale))
    return CycleCalibration(law, build(q), params, cycles, result.residuals * scale, given, result,
                            closure_offset=offset)
