# SPDX-License-Identifier: MIT
"""Transmissivity with history, T(Δ, Δ_m): the joint's flow on unloading remembers the largest
closure Δ_m it reached (docs/flow.md, "Transmissivity with history (issue 41)").

Laboratory flow through joints under a normal-load cycle is lower on unloading than on first
loading at the same closure, and does not come back to its start when the load is removed (the
granodiorite cores of issue 41: unloading/loading T ratios at equal closure with medians of
0.6-0.95 between specimens, T recovering to 55-90 % of its start); damage of the asperities and
contact area that does not open again are the usual explanations. A law of the closure alone
cannot give it. This law takes a virgin law T_v(Δ) of first loading (any TransmissivityLaw of
rockjoint.flow: cubic_law, barton_jrc) and one history parameter, the hydraulic loss d:

    Δ >= Δ_m (first loading):  e_h = e_v(Δ),                                              (T1)
    Δ <  Δ_m (un/reloading):   e_h = e_v(Δ_m) + (1 - d) [e_v(Δ) - e_v(Δ_m)],              (T2)
    T = e_h³ / 12,   e_v = (12 T_v)^(1/3) the virgin hydraulic aperture,

i.e. on unloading the hydraulic aperture recovers the fraction 1 - d of what the virgin curve
would give back between Δ_m and Δ; reloading retraces the branch up to Δ_m (it is a function of
Δ and Δ_m only), then loading continues on the virgin curve. d = 0 is the virgin law (no history);
d -> 1 keeps T at its value at the peak. The ratio unloading/loading at equal closure,

    R(Δ) = [(1 - d) + d e_v(Δ_m)/e_v(Δ)]³  (1 at Δ = Δ_m, falling as the joint opens),     (T3)

gives d from a measured ratio R at a closure Δ: d = (1 - R^(1/3)) / (1 - e_v(Δ_m)/e_v(Δ)). The
recovery after unloading to zero stress also carries the closure law's own permanent closure
(a hysteretic closure law, docs/hysteresis.md): T(Δ_p, Δ_m)/T_v(0) with Δ_p = r Δ_m.

Range of d: [0, 1); the issue's laboratory ratios 0.6-0.95 correspond to d ~ 0.03-0.8 (T3 with
e_v(Δ_m)/e_v(Δ) ~ 0.5-0.8, the ratio of the hydraulic apertures at the peak and unloaded).
SI units: m, m³.
"""
from __future__ import annotations

import numpy as np

#: the history parameter of the law: its name, what it is and its range (the registry's words)
HYDRAULIC_LOSS = ("hydraulic_loss", "d [-] in [0, 1): the fraction of the virgin hydraulic aperture's "
                  "recovery between the largest closure and the current one that unloading does not give back")


def check_loss(value) -> float:
    """d as a float in [0, 1) (ValueError naming hydraulic_loss otherwise)."""
    d = float(value)
    if not (np.isfinite(d) and 0.0 <= d < 1.0):
        raise ValueError(f"transmissivity law 'hydraulic_history': {HYDRAULIC_LOSS[0]} = {value!r} "
                         "must be in [0, 1) (0: no history; 1 would keep T at the peak's for good)")
    return d


def branch_hydraulic_aperture(virgin_now, virgin_peak, loss: float) -> np.ndarray:
    """e_h [m] of (T1-T2) from the virgin hydraulic apertures at the current closure and at the
    largest closure reached (arrays of one shape): the virgin one where the joint is at or past
    its largest closure."""
    now, peak = np.asarray(virgin_now, dtype=float), np.asarray(virgin_peak, dtype=float)
    return np.where(now <= peak, now, peak + (1.0 - loss) * (now - peak))


class HistoryTransmissivityLaw:
    """T(Δ, Δ_m) [m³] of (T1-T2) over a virgin transmissivity law `virgin` (a TransmissivityLaw
    of rockjoint.flow) with hydraulic loss `loss` d in [0, 1). ``has_history`` says the FE flow to
    pass each joint point's largest closure (fem.water.joint_flow.point_transmissivity)."""

    has_history = True

    def __init__(self, virgin, loss: float, key: str = "hydraulic_history"):
        self.key = key
        self.virgin = virgin
        self.loss = check_loss(loss)
        self.parameters = dict(virgin.parameters, virgin=virgin.key, hydraulic_loss=self.loss)

    def _pair(self, closure, maximum_closure):
        d = np.asarray(closure, dtype=float)
        if np.any(np.isnan(d)):
            raise ValueError("transmissivity law: closure contains NaN")
        if maximum_closure is None:
            return d, d
        dm = np.asarray(maximum_closure, dtype=float)
        if np.any(np.isnan(dm)):
            raise ValueError("transmissivity law: maximum_closure contains NaN")
        return d, np.maximum(dm, d)   # the current closure is reached by definition

    def hydraulic_aperture(self, closure, maximum_closure=None):
        """e_h [m] at closure(s) Δ [m] after the largest closure(s) Δ_m [m] (None: Δ_m = Δ, first
        loading, the virgin law)."""
        d, dm = self._pair(closure, maximum_closure)
        out = branch_hydraulic_aperture(self.virgin.hydraulic_aperture(d),
                                        self.virgin.hydraulic_aperture(dm), self.loss)
        return float(out) if np.ndim(out) == 0 else out

    def transmissivity(self, closure, maximum_closure=None):
        """T = e_h³/12 [m³] at closure(s) Δ [m] after the largest closure(s) Δ_m [m] (T1-T2)."""
        e_h = np.asarray(self.hydraulic_aperture(closure, maximum_closure))
        out = e_h ** 3 / 12.0
        return float(out) if np.ndim(out) == 0 else out

    def mechanical_aperture(self, closure):
        """The virgin law's mean mechanical aperture e [m] at closure(s) Δ [m] (the closure law's
        history, not this law's, sets Δ)."""
        return self.virgin.mechanical_aperture(closure)

    def transmissivity_path(self, closure) -> np.ndarray:
        """T [m³] along a closure path in order (load cycles), Δ_m the running maximum of the path."""
        d = np.asarray(closure, dtype=float).ravel()
        return np.asarray(self.transmissivity(d, np.maximum.accumulate(d)), dtype=float)

    def __repr__(self) -> str:
        shown = {k: v for k, v in self.parameters.items() if np.isscalar(v)}
        return f"HistoryTransmissivityLaw({self.key!r}, {shown})"
