# SPDX-License-Identifier: MIT
"""Calibration of a closure law to a measured closure curve (docs/theory.md §9).

A loading curve (normal stress σ_i, joint closure Δ_i) is read from a CSV file whose header
names the columns and their units, optionally corrected for the intact specimen's own
deformation (Δ = u - σ L/E, theory §0), and a law is fitted to it by Levenberg-Marquardt
(GSL ``gsl_multifit_nlinear`` through ``rockjoint._rockjoint.calibration.fit_curve``).

What is fitted (the stress is the controlled variable, the closure carries the noise):
residuals in closure, r_i = Δ_law(σ_i; p) - c - Δ_i, with c an optional closure offset (the
law's closure at the curve's zero, when the curve does not start at the law's datum).
Positive parameters are fitted as logarithms, so the search space has no boundary; their
standard uncertainties are σ_p = p σ_ln p (first order). Uncertainties come from the
covariance s²(JᵀWJ)⁻¹ scaled by the residual variance s² = χ²/(N - P).

Fitted parameters per law (the others are given):
- ``barton_bandis``: K_ni, V_m;
- ``exponential``: V_m, σ_c;
- ``greenwood_williamson``: η and σ_s (E*, β given; seated at the law's default datum);
- ``tang_jiao``: η and σ_s of its base law (GW or Tang substrate, E* and β given; R = β).

SI inside; the file and the printed report use the units the user reads (mm, MPa).
"""
from __future__ import annotations

import csv
import logging
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np

from . import law_registry
from .units import DIMENSIONS
from ._rockjoint import calibration as _cpp_calibration
from ._rockjoint.constitutive import ClosureLaw
from .law_registry import Quantity, calibratable, get
from .tabulation import DEFAULT_TOLERANCE, tabulate

__all__ = ["ClosureCurve", "FittedParameter", "Calibration", "read_closure_curve",
           "calibrate", "calibratable_laws"]

log = logging.getLogger(__name__)

#: unit name -> factor to SI, per dimension (rockjoint.units: the one table; stresses any case)
_LENGTH_UNITS = DIMENSIONS["length"]
_STRESS_UNITS = {unit.lower(): factor for unit, factor in DIMENSIONS["stress"].items()}
#: column quantity -> (accepted names, unit table)
_QUANTITIES = {
    "closure": (("closure",), _LENGTH_UNITS),
    "displacement": (("displacement",), _LENGTH_UNITS),
    "normal_stress": (("normal_stress", "stress"), _STRESS_UNITS),
    "closure_std": (("closure_std", "closure_uncertainty"), _LENGTH_UNITS),
}
_HEADER = re.compile(r"^\s*([A-Za-z_ ]+?)\s*(?:\[([^\]]*)\]|\(([^)]*)\)|_([A-Za-zµ]+))\s*$")


@dataclass
class ClosureCurve:
    """A measured loading curve in SI: stress [Pa] and closure [m], ascending.

    ``closure_std`` [m] (optional) gives the weights 1/std² of the fit. ``lines`` are the file's
    line numbers of the rows (for messages); ``source`` names the file.
    """
    normal_stress: np.ndarray
    closure: np.ndarray
    closure_std: Optional[np.ndarray] = None
    lines: Optional[np.ndarray] = None
    source: str = "<array>"

    def __post_init__(self) -> None:
        self.normal_stress = np.asarray(self.normal_stress, dtype=float)
        self.closure = np.asarray(self.closure, dtype=float)
        if self.lines is None:
            self.lines = np.arange(1, self.closure.size + 1)
        _check_curve(self)


def _where(curve: ClosureCurve, i: int) -> str:
    return f"{curve.source}: line {int(curve.lines[i])}"


def check_points(data, what: str = "a closure curve is a loading curve") -> None:
    """Clear errors naming the file and line (data.source, data.lines) for stress/closure points
    that are not 1-D arrays of one length, not finite, or at a negative (tensile) stress."""
    s, d = data.normal_stress, data.closure
    if s.shape != d.shape or s.ndim != 1:
        raise ValueError(f"{data.source}: normal_stress and closure must be 1-D arrays of one "
                         f"length (got {s.shape} and {d.shape})")
    for name, v in (("normal stress", s), ("closure", d)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ValueError(f"{_where(data, bad[0])}: {name} is {v[bad[0]]} (not finite)")
    neg = np.flatnonzero(s < 0)
    if neg.size:
        raise ValueError(f"{_where(data, neg[0])}: normal stress {s[neg[0]]:.6g} Pa is "
                         f"negative (compression is positive; {what})")


def _check_curve(curve: ClosureCurve, minimum_points: int = 4) -> None:
    """Clear errors naming the file and line for a curve that cannot be fitted."""
    check_points(curve)
    s, d = curve.normal_stress, curve.closure
    if s.size < minimum_points:
        raise ValueError(f"{curve.source}: {s.size} data point(s); at least {minimum_points} "
                         "are needed to fit a closure law")
    for name, v in (("normal stress", s), ("closure", d)):
        back = np.flatnonzero(np.diff(v) <= 0)
        if back.size:
            i = back[0] + 1
            raise ValueError(f"{_where(curve, i)}: {name} {v[i]:.6g} does not increase "
                             f"(previous row {v[i - 1]:.6g}); a loading curve needs strictly "
                             "increasing stress and closure (non-monotone curve)")
    if curve.closure_std is not None:
        std = np.asarray(curve.closure_std, dtype=float)
        bad = np.flatnonzero(~(np.isfinite(std) & (std > 0)))
        if std.shape != d.shape:
            raise ValueError(f"{curve.source}: closure_std must have one value per row")
        if bad.size:
            raise ValueError(f"{_where(curve, bad[0])}: closure_std {std[bad[0]]} must be "
                             "finite and > 0")
        curve.closure_std = std


def _parse_header(path: str, header: Sequence[str]) -> Dict[str, tuple]:
    """quantity -> (column index, SI factor) from header cells like 'closure [mm]'."""
    columns: Dict[str, tuple] = {}
    for j, cell in enumerate(header):
        m = _HEADER.match(cell)
        if not m:
            continue
        name = m.group(1).strip().lower().replace(" ", "_")
        unit = next(g for g in m.groups()[1:] if g is not None).strip()
        for quantity, (names, units) in _QUANTITIES.items():
            if name in names:
                factor = units.get(unit.lower() if units is _STRESS_UNITS else unit)
                if factor is None:
                    raise ValueError(f"{path}: line 1: column '{cell}' has unit '{unit}'; "
                                     f"use one of {', '.join(sorted(set(units)))}")
                columns[quantity] = (j, factor)
    return columns


def read_closure_curve(path, *, intact_length: Optional[float] = None,
                       young_modulus: Optional[float] = None) -> ClosureCurve:
    """Read a loading curve from a CSV file.

    The header names the columns with their units, e.g. ``closure [mm], normal_stress [MPa]``
    (also ``closure_mm``, ``normal_stress (kPa)``; lengths m/mm/um, stresses Pa/kPa/MPa/GPa).
    Instead of ``closure`` a column ``displacement`` of the jointed specimen may be given with
    ``intact_length`` L [m] and ``young_modulus`` E [Pa] of the intact rock: the closure is then
    u - σ L/E (theory §0). An optional ``closure_std`` column weights the fit by 1/std².
    Lines starting with '#' and blank lines are skipped. Errors name the file and line.
    """
    return ClosureCurve(*read_columns(path, intact_length=intact_length,
                                      young_modulus=young_modulus))


def read_rows(path, what: str) -> list:
    """[(line number, cells)] of a CSV file's rows, blank lines and lines starting with '#'
    skipped; ValueError naming the file if it cannot be read (`what` it should hold) or is empty."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = [(k + 1, r) for k, r in enumerate(csv.reader(f))]
    except OSError as err:
        raise ValueError(f"{path}: cannot read {what} ({err.strerror})") from err
    rows = [(k, r) for k, r in rows if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")]
    if not rows:
        raise ValueError(f"{path}: the file is empty")
    return rows


def read_columns(path, *, intact_length: Optional[float] = None,
                 young_modulus: Optional[float] = None) -> tuple:
    """(stress [Pa], closure [m], closure_std [m] or None, line numbers, source) of a closure CSV
    file in file order (read_closure_curve's format; also load cycles, cycle_calibration.py)."""
    path = str(path)
    rows = read_rows(path, "the closure curve")
    header_line, header = rows[0]
    columns = _parse_header(path, header)
    if "normal_stress" not in columns:
        raise ValueError(f"{path}: line {header_line}: no normal stress column; the header "
                         "needs e.g. 'closure [mm], normal_stress [MPa]' (got "
                         f"{', '.join(header)})")
    has_closure, has_displacement = "closure" in columns, "displacement" in columns
    if has_closure == has_displacement:
        raise ValueError(f"{path}: line {header_line}: the header needs exactly one of a "
                         "'closure [unit]' or a 'displacement [unit]' column (got "
                         f"{', '.join(header)})")
    if has_displacement and (intact_length is None or young_modulus is None):
        raise ValueError(f"{path}: the curve gives the specimen displacement; the intact "
                         "specimen's deformation σL/E can only be removed with its length and "
                         "Young's modulus (--intact-length, --young)")
    if has_closure and intact_length is not None:
        raise ValueError(f"{path}: the curve gives joint closure already; an intact length "
                         "applies to a 'displacement' column only")
    wanted = {q: c for q, c in columns.items()}
    data = {q: [] for q in wanted}
    lines = []
    for k, r in rows[1:]:
        for q, (j, factor) in wanted.items():
            cell = r[j].strip() if j < len(r) else ""
            try:
                v = float(cell)
            except ValueError:
                raise ValueError(f"{path}: line {k}: {q} '{cell}' is not a number") from None
            if math.isnan(v):
                raise ValueError(f"{path}: line {k}: {q} is NaN")
            data[q].append(v * factor)
        lines.append(k)
    stress = np.array(data["normal_stress"])
    std = np.array(data["closure_std"]) if "closure_std" in data else None
    if has_displacement:
        for name, v in (("intact_length", intact_length), ("young_modulus", young_modulus)):
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"{name} = {v} must be finite and > 0")
        closure = np.array(data["displacement"]) - stress * intact_length / young_modulus
        source = f"{path} (intact deformation σL/E removed, L = {intact_length * 1e3:g} mm, " \
                 f"E = {young_modulus * 1e-9:g} GPa)"
    else:
        closure = np.array(data["closure"])
        source = path
    return stress, closure, std, np.array(lines), source


# ---- what a calibration fits: the law registry's CalibrationSpec of each law -----------------
#: the closure offset Δ_0 (fitted besides a law's own unknowns; cycle_calibration's seating offset)
CLOSURE_OFFSET = Quantity("closure_offset", "Δ_0", "mm")


def calibratable_laws() -> list:
    """Keys of the laws `calibrate` can fit (rockjoint.law_registry.calibratable)."""
    return calibratable()


@dataclass
class FittedParameter:
    """One fitted parameter: SI value and standard uncertainty, with its display unit."""
    name: str
    symbol: str
    value: float
    standard_error: float
    unit: str
    scale: float  # SI per display unit

    def __str__(self) -> str:
        v, e = self.value / self.scale, self.standard_error / self.scale
        rel = f" ({100 * self.standard_error / abs(self.value):.2g} %)" if self.value else ""
        return f"{self.symbol:>4} = {v:.6g} ± {e:.2g} {self.unit}{rel}"


@dataclass
class Calibration:
    """Result of ``calibrate``: the fitted law and the statistics of the fit.

    Measured closure is modelled as ``law.closure_at_stress(σ) - closure_offset``.
    """
    law_name: str
    law: ClosureLaw
    parameters: List[FittedParameter]
    closure_offset: float                  # [m] (0 if not fitted)
    curve: ClosureCurve
    residuals: np.ndarray                  # model - data closure [m]
    given: Dict[str, object] = field(default_factory=dict)
    fit: object = None                     # the CurveFitResult

    @property
    def residual_rms(self) -> float:
        """Root mean square closure residual [m]."""
        return float(np.sqrt(np.mean(self.residuals ** 2)))

    @property
    def residual_std(self) -> float:
        """s = √(χ²/(N-P)) in closure [m] (unweighted fits), the noise estimate."""
        n, p = self.residuals.size, len(self.parameters)
        return float(np.sqrt(np.sum(self.residuals ** 2) / (n - p)))

    def predicted_closure(self, normal_stress) -> np.ndarray:
        """Closure [m] the fitted law predicts on the curve's datum at stress [Pa]."""
        return closure_of(self.law, np.asarray(normal_stress, float)) - self.closure_offset

    def parameter(self, name: str) -> FittedParameter:
        """The fitted parameter called name (KeyError if the law has none)."""
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def report(self) -> str:
        """Plain-text summary (units in every line)."""
        lines = [f"calibration of '{self.law_name}' to {self.curve.source}",
                 f"  {self.curve.closure.size} points, normal stress "
                 f"{self.curve.normal_stress[0] * 1e-6:.4g}-"
                 f"{self.curve.normal_stress[-1] * 1e-6:.4g} MPa, closure "
                 f"{self.curve.closure[0] * 1e3:.4g}-{self.curve.closure[-1] * 1e3:.4g} mm"]
        for k, v in self.given.items():
            lines.append(f"  given: {k} = {v}")
        lines.append("  fitted parameters (± standard uncertainty from the covariance scaled "
                     "by the residual variance):")
        lines += [f"    {p}" for p in self.parameters]
        lines.append(f"  residual: rms {self.residual_rms * 1e6:.4g} µm, s = √(χ²/(N-P)) "
                     f"{self.residual_std * 1e6:.4g} µm, max "
                     f"{np.max(np.abs(self.residuals)) * 1e6:.4g} µm of closure")
        if self.fit is not None:
            lines.append(f"  Levenberg-Marquardt: {self.fit.iterations} iterations, "
                         f"{self.fit.function_evaluations} model evaluations, "
                         f"{self.fit.message}")
        return "\n".join(lines)

    def table(self, max_stress: Optional[float] = None, tolerance: float = DEFAULT_TOLERANCE):
        """The fitted law tabulated up to ``max_stress`` [Pa] (default: the curve's maximum)."""
        top = float(max_stress if max_stress is not None else self.curve.normal_stress[-1])
        return tabulate(self.law, max_stress=top, tolerance=tolerance)

    def plot(self, path) -> None:
        """PNG: data and fitted curve (stress against closure), and closure residuals."""
        import matplotlib  # optional and slow to import: only when a picture is drawn
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        c = self.curve
        top_stress = c.normal_stress[-1]
        s_fine = np.concatenate([[0.0], np.geomspace(1e-4 * top_stress, top_stress, 300)])
        fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=False,
                                          gridspec_kw={"height_ratios": [2.2, 1]})
        top.plot(c.closure * 1e3, c.normal_stress * 1e-6, "o", ms=4, label="measured")
        top.plot(self.predicted_closure(s_fine) * 1e3, s_fine * 1e-6, "-",
                 label=f"fitted {self.law_name}")
        top.set_xlabel("closure Δ (datum of the curve) [mm]")
        top.set_ylabel("normal stress σ [MPa]")
        top.legend(loc="upper left")
        top.set_title(", ".join(f"{p.symbol} = {p.value / p.scale:.4g} ± "
                                f"{p.standard_error / p.scale:.2g} {p.unit}"
                                for p in self.parameters), fontsize=8)
        bottom.axhline(0.0, color="0.6", lw=0.8)
        bottom.plot(c.normal_stress * 1e-6, self.residuals * 1e6, "o", ms=4)
        bottom.set_xlabel("normal stress σ [MPa]")
        bottom.set_ylabel("residual Δ_fit - Δ [µm]")
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


def closure_of(law: ClosureLaw, stress: np.ndarray) -> np.ndarray:
    """Δ(σ) [m]; beyond a law's validity limit (Tang & Jiao) the closure there (a flat,
    continuous continuation, so the fit is steered back instead of stopped)."""
    top = law.maximum_closure
    if math.isfinite(top):
        limit = float(law.normal_stress(top))
        if math.isfinite(limit):
            stress = np.minimum(stress, limit)
    return np.asarray(law.closure_at_stress(stress), dtype=float)


def calibration_spec(law: str, composite_modulus, summit_radius, who: str) -> tuple:
    """(the registry's CalibrationSpec of `law`, {given input: value}) with clear errors for a law
    that cannot be calibrated or a missing/invalid E* or β it needs; `who` names the caller."""
    spec = get(law).calibration
    if spec is None:
        raise ValueError(f"{who}: law '{law}' cannot be calibrated; choose one of "
                         f"{', '.join(calibratable())}")
    given: Dict[str, object] = {}
    inputs = {"composite_modulus": composite_modulus, "summit_radius": summit_radius}
    for q in spec.needs:   # E*, β: their names, units and ranges from the registry (the C++ specs)
        v = inputs[q.name]
        if v is None or q.problem(v):
            raise ValueError(f"{who}: law '{law}' needs {q.name} [{q.spec.unit}] {q.range} (got {v})")
        given[q.name] = float(v)
    return spec, given


def calibrate(curve: ClosureCurve, law: str, *, composite_modulus: Optional[float] = None,
              summit_radius: Optional[float] = None, distribution: str = "gaussian",
              base: Optional[str] = None, variant: str = "I1",
              base_radius: Optional[float] = None, fit_offset: Optional[bool] = None,
              initial: Optional[Sequence[float]] = None,
              maximum_iterations: int = 500) -> Calibration:
    """Fit ``law`` to ``curve`` by Levenberg-Marquardt; see the module docstring.

    ``composite_modulus`` E* [Pa] and ``summit_radius`` β [m] are required for the GW-type laws
    (``greenwood_williamson``, ``tang_jiao``); ``distribution`` (gaussian/exponential),
    ``base`` (tang_substrate/greenwood_williamson, for tang_jiao), ``variant`` (I1/I2) and
    ``base_radius`` r0 [m] complete them. ``fit_offset`` (default: True for GW-type laws,
    False for the empirical ones) adds the closure offset Δ_0. ``initial`` overrides the
    starting values (SI, in the order of the fitted parameters). Weights: 1/closure_std² when
    the curve has it.
    """
    spec, given = calibration_spec(law, composite_modulus, summit_radius, "calibrate")
    if not spec.needs and (composite_modulus is not None or summit_radius is not None):
        log.info("calibrate: %s ignores composite_modulus/summit_radius", law)
    options = {"distribution": distribution, "base": base or law_registry.DEFAULT_TANG_JIAO_BASE, "variant": variant,
               "base_radius": None if base_radius is None else float(base_radius)}
    given.update({k: options[k] for k in spec.options if options[k] is not None})
    offset = spec.fit_offset if fit_offset is None else bool(fit_offset)
    unknowns = list(spec.unknowns) + ([CLOSURE_OFFSET] if offset else [])
    if curve.closure.size <= len(unknowns) + 1:
        raise ValueError(f"{curve.source}: {curve.closure.size} points are too few to fit "
                         f"{len(unknowns)} parameters with an uncertainty (need at least "
                         f"{len(unknowns) + 2})")
    start = (list(initial) if initial is not None else
             spec.initial_guess(curve.normal_stress, curve.closure, given, spec.build, offset, closure_of))
    if len(start) != len(unknowns):
        raise ValueError(f"calibrate: {len(start)} initial values for {len(unknowns)} "
                         f"parameters ({', '.join(u.name for u in unknowns)})")
    npos = len(spec.unknowns)
    if any(not (math.isfinite(v) and v > 0) for v in start[:npos]):
        raise ValueError(f"calibrate: initial values {start[:npos]} must be finite and > 0")

    # Fitted vector q: ln p for the law's parameters, Δ_0/scale for the offset; residuals in
    # units of the curve's closure range so that GSL's tolerances see O(1) numbers.
    scale = float(np.max(np.abs(curve.closure))) or 1.0

    def unpack(q):
        values = [math.exp(x) for x in q[:npos]]
        return values, (q[npos] * scale if offset else 0.0)

    def model(q):
        values, c = unpack(q)
        fitted = spec.build(values, given)
        return (closure_of(fitted, curve.normal_stress) - c) / scale

    q0 = [math.log(v) for v in start[:npos]] + ([start[npos] / scale] if offset else [])
    weights = None if curve.closure_std is None else (scale / curve.closure_std) ** 2
    result = _cpp_calibration.fit_curve(model, curve.closure / scale, np.array(q0), weights,
                                        maximum_iterations=maximum_iterations)
    if not result.converged:
        log.warning("calibrate: %s", result.message)
    q, se = result.parameters, result.standard_errors
    values, c = unpack(q)
    fitted_law = spec.build(values, given)
    params = []
    for j, u in enumerate(unknowns):
        if j < npos:
            v, e = values[j], values[j] * se[j]      # σ_p = p σ_ln p
        else:
            v, e = c, se[j] * scale
        params.append(FittedParameter(u.name, u.symbol, v, e, u.unit, u.scale))
    shown, needs = {}, {q.name: q for q in spec.needs}
    for k, v in given.items():   # in the units of files and reports
        shown[k] = (f"{v / needs[k].scale:.6g} {needs[k].unit}" if k in needs else
                    f"{v * 1e3:.6g} mm" if k == "base_radius" else v)
    return Calibration(law, fitted_law, params, c, curve, result.residuals * scale, shown,
                       result)
