# SPDX-License-Identifier: MIT
"""Calibration of the transmissivity law with history to measured flow cycles
(`rockjoint calibrate --flow`; docs/flow.md "Transmissivity with history (issue 41)").

The data (flow_cycles.py): normal stress σ_i in test order, transmissivity T_i, and the closure
Δ_i where measured. The model: the law ``hydraulic_history`` (flow_history.py, T1-T2) over a virgin
law (cubic_law or barton_jrc) at the closure Δ_i and the largest closure so far Δ_m,i. Where does
Δ come from:

* measured closure: Δ_i itself (the data's datum: e0 is then the aperture at the first point) and
  Δ_m,i its running maximum. The closure law, if named, is fitted to the same cycles by
  cycle_calibration.calibrate_cycles (a separate least-squares problem: with Δ measured the flow
  parameters do not enter the closure residuals, nor the closure law's the flow residuals);
* no closure column, a closure law given (any ClosureLaw, NormalHysteresis for branches): its path;
* no closure column, a calibratable closure law named: fitted together with the flow, as a
  NormalHysteresis (the virgin law's unknowns, r, m; the law's datum, no seating offset: an
  offset is the same as a change of e0 for the flow).

Residuals in log10 T (T spans decades; a relative error is what a flow measurement has), fitted by
the Levenberg-Marquardt of calibration.py (GSL); e0, JRC and the closure law's unknowns as
logarithms, d and r as logits, m - 1 as a logarithm. What the data identify: each parameter's
standard uncertainty (from the covariance scaled by the residual variance: identifiable when it
is below the value, cycle_calibration.identifiable), and the singular values of the Jacobian of the
residuals in the fitted (logarithmic) variables, largest first, normalised by the largest, with
the combination of parameters the smallest one leaves undetermined.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional

import numpy as np

from . import flow
from ._rockjoint import calibration as _cpp_calibration
from ._rockjoint.constitutive import NormalHysteresis
from .calibration import FittedParameter, calibration_spec
from .cycle_calibration import BRANCHES, LoadCycles, calibrate_cycles, identifiable
from .flow_cycles import FlowCycles
from .law_registry import HISTORY_PARAMETERS

__all__ = ["FlowCalibration", "calibrate_flow"]


def _logistic(x: float) -> float:
    return 1.0 / (1.0 + math.exp(-x))


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


@dataclass
class FlowCalibration:
    """Result of calibrate_flow: the fitted law with history, the closure along the data, the
    parameters with uncertainties, log10 T residuals and the Jacobian's singular values."""

    law: object                          # the fitted flow_history.HistoryTransmissivityLaw
    parameters: List[FittedParameter]
    data: FlowCycles
    closure: np.ndarray                  # Δ along the data [m] (measured or the closure law's)
    residuals: np.ndarray                # log10 T_fit - log10 T
    singular_values: np.ndarray          # of the Jacobian in the fitted variables, largest first
    weakest: Dict[str, float]            # the combination the smallest singular value leaves free
    closure_law: object = None           # the closure law used or fitted
    closure_fit: object = None           # cycle_calibration.CycleCalibration (measured closure, law named)
    fit: object = field(default=None, repr=False)
    disagreements: List[str] = field(default_factory=list)   # where the law does not follow the data

    def fitted_transmissivity(self) -> np.ndarray:
        """T [m³] of the fitted law at each data point."""
        return np.asarray(self.law.transmissivity_path(self.closure), dtype=float)

    def branch_rms(self) -> Dict[str, float]:
        """rms of log10 T_fit - log10 T per branch (those present)."""
        labels = self.data.branches()
        return {b: float(np.sqrt(np.mean(self.residuals[labels == b] ** 2))) for b in BRANCHES
                if np.any(labels == b)}

    def not_identifiable(self) -> List[str]:
        """Names of the parameters the data do not determine (uncertainty above the value)."""
        return [p.name for p in self.parameters if not identifiable(p)]

    def parameter(self, name: str) -> FittedParameter:
        """The fitted parameter `name` (KeyError if none)."""
        return {p.name: p for p in self.parameters}[name]

    def report(self) -> str:
        """The calibration in words: data, parameters with uncertainties, rms per branch, what the
        data identify."""
        d = self.data
        lines = [f"flow calibration of 'hydraulic_history' (virgin {self.law.virgin.key}) to {d.source}",
                 f"  {d.normal_stress.size} points, normal stress up to {np.max(d.normal_stress) * 1e-6:.4g} MPa, "
                 f"T {np.min(d.transmissivity):.3g} - {np.max(d.transmissivity):.3g} m³, closure "
                 + ("measured" if d.closure is not None else "from the closure law"),
                 "  fitted parameters (± standard uncertainty from the covariance scaled by the residual variance):"]
        for p in self.parameters:
            lines.append(f"    {p}" if identifiable(p) else
                         f"    {p.symbol:>4}   not identifiable from these data (the fit gives "
                         f"{p.value / p.scale:.3g} ± {p.standard_error / p.scale:.2g} {p.unit})")
        for b, rms in self.branch_rms().items():
            lines.append(f"  {b:9s} rms log10 T {rms:.3g} (a factor {10 ** rms:.3g})")
        s = self.singular_values
        lines.append("  Jacobian singular values / largest: " + ", ".join(f"{v / s[0]:.2g}" for v in s))
        lines.append("  least determined combination: " + " ".join(
            f"{w:+.2f} {k}" for k, w in self.weakest.items() if abs(w) >= 0.1))
        lines += [f"  the law and the data disagree: {note}" for note in self.disagreements]
        if self.closure_fit is not None:
            lines += ["  closure law fitted to the measured closures:", self.closure_fit.report()]
        return "\n".join(lines)

    def plot(self, path) -> None:
        """PNG: measured and fitted T against normal stress through the cycle (and against the
        closure), by branch."""
        import matplotlib  # optional and slow to import: only when a picture is drawn
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        d, labels, fitted = self.data, self.data.branches(), self.fitted_transmissivity()
        fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
        for ax, x, label in ((axes[0], d.normal_stress * 1e-6, "normal stress σ [MPa]"),
                             (axes[1], self.closure * 1e3, "closure Δ [mm]")):
            ax.plot(x, fitted, "-", color="0.3", lw=1, label="fitted (through the cycle)")
            for b, marker in zip(BRANCHES, "o^s"):
                on = labels == b
                if np.any(on):
                    ax.plot(x[on], d.transmissivity[on], marker, ms=4, ls="none", label=f"measured, {b}")
            ax.set_yscale("log")
            ax.set_xlabel(label)
            ax.set_ylabel("transmissivity T [m³]")
        axes[0].legend(fontsize=8)
        axes[1].set_title(", ".join(f"{p.symbol} = {p.value / p.scale:.3g}" for p in self.parameters), fontsize=7)
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


def _flow_start(data: FlowCycles, virgin: str, closure0: float, closure_max: float) -> List[float]:
    """(e0, d = 0.2[, JRC]) whose virgin law gives T(Δ_0) = T_0 at the first point's closure Δ_0
    and stays open at every closure of the data (e0 above the largest closure: a start where the
    law shuts the joint has residuals without gradient); Barton's with e = √2 e_h, inside its range
    e_h < e (e_h = e²/JRC^2.5 in µm)."""
    e_h0 = (12.0 * float(data.transmissivity[0])) ** (1.0 / 3.0)
    e_low = (12.0 * float(np.min(data.transmissivity))) ** (1.0 / 3.0)
    if virgin == "cubic_law":
        return [max(e_h0 + closure0, closure_max + e_low), 0.2]
    e0 = max(math.sqrt(2.0) * e_h0 + closure0, closure_max + math.sqrt(2.0) * e_low)
    return [e0, 0.2, (((e0 - closure0) / 1e-6) ** 2 / (e_h0 / 1e-6)) ** 0.4]


def _disagreements(data: FlowCycles, fit: "FlowCalibration") -> List[str]:
    """Where the law and the data part: a measured closure larger than the hydraulic aperture the
    flow gives (the law closes the flow path with the measured closure), a branch off by more than
    a factor 2 (rms log10 T > 0.3)."""
    notes = []
    if data.closure is not None:
        e_h0 = (12.0 * float(data.transmissivity[0])) ** (1.0 / 3.0)
        span = float(np.max(data.closure) - data.closure[0])
        if span > e_h0:
            notes.append(f"the measured closure grows by {span * 1e3:.3g} mm, {span / e_h0:.3g} times the hydraulic "
                         f"aperture of the first point ({e_h0 * 1e3:.3g} mm): the measured closure is not the closure "
                         "of the flow path (the gauge length's rock deformation, contact growth); fit without the "
                         "closure column, a closure law fitted with the flow (--law)")
    notes += [f"the {b} branch is off by a factor {10 ** rms:.3g} (rms log10 T {rms:.3g})"
              for b, rms in fit.branch_rms().items() if rms > 0.3]
    return notes


def calibrate_flow(data: FlowCycles, *, virgin: str = "cubic_law", law: Optional[str] = None,
                   closure_law=None, composite_modulus: Optional[float] = None,
                   summit_radius: Optional[float] = None, initial: Optional[List[float]] = None,
                   maximum_iterations: int = 500) -> FlowCalibration:
    """Fit ``hydraulic_history`` over `virgin` to `data` (module docstring). `law`: a calibratable
    closure law key (fitted: separately on measured closures, together without them);
    `closure_law`: a ClosureLaw given (data without closure). `initial`: starting values in SI
    (the closure law's unknowns, r, m when fitted together, then e0, d[, JRC])."""
    if virgin not in flow.HISTORY_VIRGINS:
        raise ValueError(f"calibrate_flow: virgin = {virgin!r}; expected one of {', '.join(flow.HISTORY_VIRGINS)}")
    together = data.closure is None and closure_law is None
    if together and law is None:
        raise ValueError(f"{data.source}: no closure column; name the closure law to fit with the flow "
                         "(--law) or give one (closure_law=)")
    spec, given, npos = None, {}, 0
    if together:
        spec, given = calibration_spec(law, composite_modulus, summit_radius, "calibrate_flow")
        npos = len(spec.unknowns)
    n_flow = 2 if virgin == "cubic_law" else 3
    nq = npos + (2 if together else 0) + n_flow
    if initial is not None:
        start = list(initial)
    elif together:
        # a first closure from the flow itself: the cubic law's Δ = e_h(first) - e_h on first loading
        e_h = np.cbrt(12.0 * data.transmissivity)
        virgin_on = data.branches() == "loading"
        pseudo = np.maximum(e_h[0] - e_h[virgin_on], 0.0) + 1e-3 * e_h[0]
        start = list(spec.initial_guess(data.normal_stress[virgin_on], pseudo, given, spec.build, False,
                                        lambda lw, s: np.asarray(lw.closure_at_stress(s))))[:npos]
        first = float(spec.build(start, given).closure_at_stress(data.normal_stress[:1])[0])
        path = np.asarray(spec.build(start, given).closure_at_stress(data.normal_stress), dtype=float)
        start += [0.3, 2.0] + _flow_start(data, virgin, first, float(np.max(path)))
    else:
        path = (data.closure if data.closure is not None else
                np.asarray(closure_law.closure_at_stress(data.normal_stress), dtype=float))
        first = float(path[0])
        start = _flow_start(data, virgin, first, float(np.max(path)))
    if len(start) != nq:
        raise ValueError(f"calibrate_flow: {len(start)} initial values for {nq} parameters")

    def unpack(q):
        cl = None
        if together:
            values = [math.exp(x) for x in q[:npos]]
            cl = NormalHysteresis(spec.build(values, given), _logistic(q[npos]), 1.0 + math.exp(q[npos + 1]))
        k = nq - n_flow
        e0, loss = math.exp(q[k]), _logistic(q[k + 1])
        extra = {"virgin": virgin} if virgin == "cubic_law" else {"virgin": virgin, "jrc": math.exp(q[k + 2])}
        return cl, flow.transmissivity_law("hydraulic_history", initial_aperture=e0, hydraulic_loss=loss, **extra)

    fixed = None
    if data.closure is not None:
        fixed = data.closure
    elif closure_law is not None:
        fixed = np.asarray(closure_law.closure_path(data.normal_stress) if getattr(closure_law, "has_history", False)
                           else closure_law.closure_at_stress(data.normal_stress), dtype=float)
    observed = np.log10(data.transmissivity)

    def closure_of(cl):
        return fixed if cl is None else np.asarray(cl.closure_path(data.normal_stress), dtype=float)

    def model(q):
        try:
            cl, tl = unpack(q)
            return np.log10(np.maximum(tl.transmissivity_path(closure_of(cl)), 1e-300))
        except (ValueError, OverflowError):   # a trial beyond the admissible: steer the fit back
            return np.full(observed.size, 1e3)

    q0 = [math.log(v) for v in start[:npos]]
    if together:
        q0 += [_logit(start[npos]), math.log(start[npos + 1] - 1.0)]
    k = nq - n_flow
    q0 += [math.log(start[k]), _logit(start[k + 1])] + ([math.log(start[k + 2])] if n_flow == 3 else [])
    result = _cpp_calibration.fit_curve(model, observed, np.array(q0), None, maximum_iterations=maximum_iterations)
    if together:
        # Levenberg-Marquardt can stall where the history saturates (m -> inf, r or d -> 0: no
        # gradient left); a second start from the fitted closure law with the history reset keeps
        # the second where it is clearly better (a tenth less squared misfit: a restart that only
        # slides along a valley the data leave flat, r against d, changes nothing that matters and
        # keeps the first answer; the Vogler et al. 2018 cores, docs/flow.md, need the second)
        q1 = np.concatenate([np.asarray(result.parameters)[:npos], np.asarray(q0)[npos:]])
        again = _cpp_calibration.fit_curve(model, observed, q1, None, maximum_iterations=maximum_iterations)
        if np.sum(np.square(again.residuals)) < 0.9 * np.sum(np.square(result.residuals)):
            result = again
    q, se = np.asarray(result.parameters), np.asarray(result.standard_errors)
    cl, tl = unpack(q)
    names, params = [], []
    if together:
        for j, u in enumerate(spec.unknowns):
            v = math.exp(q[j])
            params.append(FittedParameter(u.name, u.symbol, v, v * se[j], u.unit, u.scale))
        r, m = _logistic(q[npos]), 1.0 + math.exp(q[npos + 1])
        for quantity, value, error in ((HISTORY_PARAMETERS[0], r, r * (1 - r) * se[npos]),
                                       (HISTORY_PARAMETERS[1], m, (m - 1) * se[npos + 1])):
            params.append(FittedParameter(quantity.name, quantity.symbol, value, error, quantity.unit, quantity.scale))
    e0, loss = math.exp(q[k]), _logistic(q[k + 1])
    params += [FittedParameter("initial_aperture", "e0", e0, e0 * se[k], "mm", 1e-3),
               FittedParameter("hydraulic_loss", "d", loss, loss * (1 - loss) * se[k + 1], "-", 1.0)]
    if n_flow == 3:
        jrc = math.exp(q[k + 2])
        params.append(FittedParameter("jrc", "JRC", jrc, jrc * se[k + 2], "-", 1.0))
    names = [p.name for p in params]
    # the Jacobian in the fitted variables by central differences: what the data determine
    h = 1e-6
    jac = np.column_stack([(model(q + h * e) - model(q - h * e)) / (2 * h) for e in np.eye(q.size)])
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    weakest = dict(zip(names, vt[-1] * np.sign(vt[-1][np.argmax(np.abs(vt[-1]))])))
    closure_fit = None
    if data.closure is not None and law is not None:
        closure_fit = calibrate_cycles(LoadCycles(data.normal_stress, data.closure, data.lines, data.source), law,
                                       composite_modulus=composite_modulus, summit_radius=summit_radius)
    fit = FlowCalibration(tl, params, data, closure_of(cl), np.asarray(result.residuals), s, weakest,
                          cl if cl is not None else closure_law if closure_law is not None
                          else (closure_fit.law if closure_fit else None), closure_fit, result)
    fit.disagreements = _disagreements(data, fit)
    return fit
