# SPDX-License-Identifier: MIT
"""Tabulated closure laws: the fast, error-controlled form finite-element codes call.

A table is built once from any closure law (``tabulate``), saved to a self-describing
``.rjt`` file (``TabulatedLaw.save``/``TabulatedLaw.load``), and evaluated like any law.
The interpolant is a monotone C¹ Hermite cubic in Δ (a quartic in √Δ on the first segment)
whose tangent is its exact derivative (see constitutive/tabulated_law.hpp for the choices). SI units (Pa, m); plots
use MPa and mm and say so.
"""
from __future__ import annotations

from typing import Optional

import numpy as np

from ._rockjoint.constitutive import ClosureLaw, NormalHysteresis, TabulatedLaw

__all__ = ["TabulatedLaw", "tabulate", "curve_table", "plot_table", "table_errors"]


#: the tabulation defaults: the C++ TabulatedLaw::Options' own (their one spelling)
DEFAULT_TOLERANCE = TabulatedLaw.default_tolerance
DEFAULT_MAXIMUM_KNOTS = TabulatedLaw.default_maximum_knots


def tabulate(law: ClosureLaw, *, max_stress: Optional[float] = None,
             max_closure: Optional[float] = None, tolerance: float = DEFAULT_TOLERANCE,
             residual_stiffness: Optional[float] = None,
             maximum_knots: int = DEFAULT_MAXIMUM_KNOTS) -> ClosureLaw:
    """Tabulate ``law`` up to ``max_stress`` [Pa] or over [0, ``max_closure``] [m]: a TabulatedLaw,
    or for a law with history (NormalHysteresis) the same law over its tabulated virgin curve
    (a table holds one curve; the branches are closed forms of it, docs/hysteresis.md).

    ``tolerance`` bounds the relative error of σ and of k against ``law``;
    ``residual_stiffness`` k_res [Pa/m] applies for Δ <= 0 (None: 1e-6 σ_max/Δ_max; 0: the
    strict σ = k = 0). Raises ValueError for a bad range/option or a law that cannot be
    tabulated there, RuntimeError if ``maximum_knots`` is not enough.

    The table meets its tolerance against the closed form of a Barton-Bandis law between its
    knots (Δ = 0.123 mm is no knot: the first knot past it is printed):

    >>> from rockjoint import BartonBandis
    >>> law = BartonBandis(2e10, 3e-4)
    >>> table = tabulate(law, max_stress=10e6, tolerance=1e-6)
    >>> bool(abs(table.normal_stress(1.23e-4) / law.normal_stress(1.23e-4) - 1) <= 1e-6)
    True
    >>> bool(abs(table.normal_stiffness(1.23e-4) / law.normal_stiffness(1.23e-4) - 1) <= 1e-6)
    True
    >>> round(table.table_maximum_stress / 1e6, 9)   # the last knot carries σ_max [MPa]
    10.0
    """
    if (max_stress is None) == (max_closure is None):
        raise ValueError("tabulate: give exactly one of max_stress [Pa] or max_closure [m]")
    if isinstance(law, NormalHysteresis):
        virgin = tabulate(law.virgin, max_stress=max_stress, max_closure=max_closure, tolerance=tolerance,
                          residual_stiffness=residual_stiffness, maximum_knots=maximum_knots)
        return NormalHysteresis(virgin, law.permanent_fraction, law.unloading_exponent)
    if max_stress is not None:
        return TabulatedLaw.from_stress(law, float(max_stress), tolerance, residual_stiffness,
                                        int(maximum_knots))
    return TabulatedLaw.from_closure(law, float(max_closure), tolerance, residual_stiffness,
                                     int(maximum_knots))


def curve_table(law: ClosureLaw) -> TabulatedLaw:
    """The table holding a tabulated law's curve: the law itself, or for a law with history the
    table of its virgin curve (what ``tabulate`` made of it). TypeError for an untabulated law."""
    table = law.virgin if isinstance(law, NormalHysteresis) else law
    if not isinstance(table, TabulatedLaw):
        raise TypeError(f"curve_table: {law.name} is not tabulated (rockjoint.tabulate makes it a table)")
    return table


def _sample_closures(table: TabulatedLaw, per_interval: int = 16) -> np.ndarray:
    """Closures between every pair of knots: uniform in Δ, and in √Δ on the first interval
    (each segment in the variable it is interpolated in)."""
    d = table.knot_closure
    frac = (np.arange(1, per_interval + 1) - 0.5) / per_interval
    first = (frac * np.sqrt(d[1])) ** 2
    inner = (d[1:-1, None] + frac[None, :] * np.diff(d[1:])[:, None]).ravel()
    return np.concatenate([first, inner])


def table_errors(table: TabulatedLaw, source: ClosureLaw, per_interval: int = 16):
    """(Δ [m], relative σ error, relative k error) of ``table`` against ``source``, sampled
    between the knots."""
    d = _sample_closures(table, per_interval)
    d = d[d > 0]
    s_tab, k_tab, _, _ = table.evaluate(d)
    s_src, k_src, _, _ = source.evaluate(d)
    return d, np.abs(s_tab / s_src - 1.0), np.abs(k_tab / k_src - 1.0)


def plot_table(table: TabulatedLaw, source: Optional[ClosureLaw] = None,
               path: Optional[str] = None, title: Optional[str] = None):
    """Figure of a table (and its source if given): σ(Δ) and k(σ) on log axes, the relative
    error between knots, and the extension rules around [0, Δ_max]. Saved to ``path`` (PNG)
    if given. Uses the Agg canvas (no display needed). Returns the matplotlib Figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # optional, slow: only when plotting
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 8.5), constrained_layout=True)
    FigureCanvasAgg(fig)
    ax = fig.subplots(2, 2)
    mm, mpa, mpa_mm = 1e3, 1e-6, 1e-9
    dmax = table.table_maximum_closure
    d = np.geomspace(dmax * 1e-6, dmax, 600)
    s, k, _, _ = table.evaluate(d)
    kd, ks = table.knot_closure[1:], table.knot_stress[1:]
    kk = table.knot_stiffness[1:]

    a = ax[0, 0]
    if source is not None:
        ss, _, _, _ = source.evaluate(d)
        a.loglog(d * mm, ss * mpa, color="0.6", lw=4, label=f"source: {source.name}")
    a.loglog(d * mm, s * mpa, color="C0", lw=1.2, label="table")
    a.loglog(kd * mm, ks * mpa, "k.", ms=2, label=f"{table.knot_count} knots")
    a.set_xlabel("closure Δ [mm]")
    a.set_ylabel("normal stress σ [MPa]")
    a.set_title("σ(Δ)")
    a.legend(fontsize=8)

    a = ax[0, 1]
    if source is not None:
        ss, kss, _, _ = source.evaluate(d)
        a.loglog(ss * mpa, kss * mpa_mm, color="0.6", lw=4, label="source")
    a.loglog(s * mpa, k * mpa_mm, color="C1", lw=1.2, label="table")
    a.loglog(ks * mpa, kk * mpa_mm, "k.", ms=2, label="knots")
    a.set_xlabel("normal stress σ [MPa]")
    a.set_ylabel("normal stiffness k [MPa/mm]")
    a.set_title("k(σ)")
    a.legend(fontsize=8)

    a = ax[1, 0]
    if source is not None:
        de, es, ek = table_errors(table, source)
        tiny = 1e-17  # show exact agreement on a log axis
        a.loglog(de * mm, np.maximum(es, tiny), ".", ms=1.5, color="C0", label="σ")
        a.loglog(de * mm, np.maximum(ek, tiny), ".", ms=1.5, color="C1", label="k")
        a.axhline(table.tolerance, color="r", lw=1, label=f"tolerance {table.tolerance:g}")
        a.set_ylim(tiny, max(10 * table.tolerance, 1e-15))
        a.legend(fontsize=8, markerscale=6)
    else:
        a.text(0.5, 0.5, "no source law given", ha="center", va="center",
               transform=a.transAxes)
    a.set_xlabel("closure Δ [mm]")
    a.set_ylabel("relative error vs source [-]")
    a.set_title("error between knots")

    a = ax[1, 1]
    dl = np.linspace(-0.1 * dmax, 1.3 * dmax, 800)
    sl, kl, _, _ = table.evaluate(dl)
    a.plot(dl * mm, sl * mpa, color="C0", label="table (with extensions)")
    if source is not None:
        inside = (dl > 0) & (dl < min(source.maximum_closure, 1.3 * dmax))
        ssrc, _, _, _ = source.evaluate(dl[inside])
        a.plot(dl[inside] * mm, ssrc * mpa, "--", color="0.5", label="source")
    a.axvline(dmax * mm, color="r", lw=0.8, label="Δ_max: linear continuation")
    a.axvline(0.0, color="k", lw=0.5)
    top = 1.3 * table.table_maximum_stress * mpa
    a.set_ylim(-0.05 * top, top)
    a.set_xlabel("closure Δ [mm]")
    a.set_ylabel("normal stress σ [MPa]")
    a.set_title(f"extensions (open: k_res = {table.residual_stiffness * mpa_mm:.3g} MPa/mm)")
    a.legend(fontsize=8)

    fig.suptitle(title or f"Tabulated {table.source_model}: {table.knot_count} knots, "
                 f"tolerance {table.tolerance:g}")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
