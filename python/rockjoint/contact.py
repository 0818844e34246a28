# SPDX-License-Identifier: MIT
"""Exact elastic contact of a joint's own topography: the boundary-element reference every
closure law is measured against (docs/contact.md).

The two walls' frictionless elastic contact is that of a rigid surface carrying the composite
topography with a half-space of modulus E* (theory §1). Given the aperture field of a contact
state (``topography.composite_topography(...).aperture``), :func:`closure_curve` solves it at a
sequence of nominal stresses (Polonsky-Keer constrained conjugate gradients on an FFT kernel,
warm-started from load to load) and :func:`exact_elastic_law` turns the curve into a
:class:`rockjoint.TabulatedLaw` that the FE coupling uses like any other table.

With ``flow=True`` each load also gives the transmissivity of its gap field (the mechanical
aperture under load; rockjoint.flow, docs/flow.md): the columns transmissivity_xx/yy/xy and
hydraulic_aperture, and ``flow.transmissivity_law("walls", curve=curve)`` tabulates T(Δ).

SI units: Pa, m. Closure is measured from first contact, net of the bulk deformation of the
blocks (theory §0; periodic kernel: mean displacement 0; non-periodic: the mean displacement of
the patch under uniform σ is subtracted, the raw rigid approach is kept as ``approach``).
"""
from __future__ import annotations

import dataclasses
import logging
from typing import List, Optional, Sequence

import numpy as np

from ._rockjoint import contact as _cpp
from . import law_registry
from .flow import ApertureFlow, Transmissivity
from ._rockjoint.constitutive import ClosureLaw
from ._rockjoint.topography import Surface

log = logging.getLogger(__name__)

Kernel = _cpp.Kernel


@dataclasses.dataclass
class ClosureCurve:
    """The BEM answer at each nominal stress (arrays over the loads, SI)."""

    stress: np.ndarray              # σ [Pa]
    closure: np.ndarray             # Δ [m] from first contact, net of bulk deformation
    approach: np.ndarray            # d [m], raw rigid approach (= closure for periodic)
    contact_area_ratio: np.ndarray  # A/A0 [-] (node count: biased up by ~1 node row per spot edge)
    contact_patches: np.ndarray     # 4-connected contact spots
    iterations: np.ndarray          # CG iterations per load
    complementarity: np.ndarray     # max p g [Pa m]
    minimum_gap: np.ndarray         # min g off contact [m]
    plastic_area_ratio: np.ndarray  # fraction of the points at the pressure cap H [-]
    mean_flattening: np.ndarray     # mean plastic flattening so far [m]
    composite_modulus: float        # E* [Pa]
    spacing: float                  # h [m]
    shape: tuple                    # grid (rows, cols)
    periodic: bool
    tolerance: float
    hardness: float = float("inf")  # H [Pa] (inf: elastic walls)
    unloaded_closure: float = 0.0   # closure [m] with the load removed after the path (permanent)
    pressure: Optional[List[np.ndarray]] = None   # p [Pa] per load (keep_fields=True)
    gap: Optional[List[np.ndarray]] = None        # g [m] per load: the mechanical aperture
    # flow=True (rockjoint.flow): per load, T [m³] of the gap field (q̄ = -(T/μ) ∇p̄), the
    # symmetric part's off-diagonal, e_h = (12 (T_xx + T_yy)/2)^(1/3) and the mean gap [m]
    transmissivity_xx: Optional[np.ndarray] = None
    transmissivity_yy: Optional[np.ndarray] = None
    transmissivity_xy: Optional[np.ndarray] = None
    hydraulic_aperture: Optional[np.ndarray] = None
    mechanical_aperture: Optional[np.ndarray] = None
    initial_flow: Optional[Transmissivity] = None         # of the aperture at first contact (Δ = 0)
    flow_results: Optional[List[Transmissivity]] = None   # the whole flow answer per load
    # profile=True (elastic walls): where each load's time went (ContactProfile [s]), the shortest
    # of 5 u = K p calls after the curve (one FFT pair: the limit per iteration), the solver's
    # set-up and the FFTW planning inside it [s]
    profile: Optional[list] = None
    transform_pair: Optional[float] = None
    setup_seconds: Optional[float] = None
    planning_seconds: Optional[float] = None
    _states: list = dataclasses.field(default_factory=list, repr=False)


def closure_curve(aperture: Surface, composite_modulus: float, stresses: Sequence[float], *,
                  periodic: bool = True, tolerance: float = 1e-8, maximum_iterations: int = 2000,
                  keep_fields: bool = False, hardness: float = float("inf"), flow: bool = False,
                  flow_solver: Optional[str] = None, profile: bool = False) -> ClosureCurve:
    """Solve the contact of `aperture` (e [m], NaN = masked, min e is taken as first contact)
    against a half-space of modulus E* [Pa] at each nominal stress in `stresses` [Pa] (> 0;
    increasing order warm-starts best). `periodic`: the grid is one period of a periodic
    surface (synthetic joints) or an isolated scan (False: zero-padded Love kernel).
    `hardness` H [Pa]: elastic-perfectly-plastic walls, the contact pressure capped at the rock's
    indentation hardness; the stresses are then a load path (load cycles: up and down in any
    order), plastic flattening persists from load to load, and `unloaded_closure` is the
    permanent closure when the load is removed at the end (docs/contact.md).
    `flow`: also the transmissivity of the gap field at each load and at first contact (elastic
    or elastic-plastic walls: the gap is exactly 0 on each load's contact set; the same boundary
    as the kernel: periodic, or sealed sides for an isolated scan; `flow_solver` as
    rockjoint.flow.transmissivity's `solver`; docs/flow.md).
    `profile` (elastic walls): time each load's phases and the solver's FFT pair (the columns
    profile, transform_pair, setup_seconds, planning_seconds; bench/bench_contact.py).
    Raises ValueError for bad input, RuntimeError if a load does not converge."""
    stresses = np.asarray(stresses, dtype=float).ravel()
    if stresses.size == 0 or not np.all(np.isfinite(stresses)) or np.any(stresses <= 0):
        raise ValueError("closure_curve: stresses must be a non-empty list of finite values > 0 Pa")
    kernel = Kernel.periodic if periodic else Kernel.non_periodic
    if not hardness > 0:
        raise ValueError(f"closure_curve: hardness = {hardness} Pa must be > 0 (inf: elastic walls)")
    rows, cols = aperture.shape
    if profile and np.isfinite(hardness):
        raise ValueError("closure_curve: profile=True times the elastic solver; hardness must be inf")
    options = _cpp.ContactOptions(tolerance, maximum_iterations, bool(profile))
    # one flow problem for every load: its symbolic factorisation is made once
    flow_of = ApertureFlow((rows, cols), (aperture.spacing_x, aperture.spacing_y),
                           periodic=periodic, **({} if flow_solver is None else {"solver": flow_solver})
                           ) if flow else None
    if np.isfinite(hardness):
        curve = _plastic_curve(aperture, composite_modulus, stresses, kernel, float(hardness),
                               options, keep_fields or flow, periodic, tolerance)
        return _with_flow(curve, aperture, flow_of, keep_fields) if flow else curve
    solver = _cpp.ElasticContact(aperture, float(composite_modulus), kernel, options)
    states, pressure, gap = [], [], []
    for i, s in enumerate(stresses):
        st, p, g = solver.solve(float(s), keep_fields or flow, rows, cols)
        if not st.converged:
            raise RuntimeError(f"closure_curve: load {i} (σ = {s:g} Pa) did not converge in "
                               f"{maximum_iterations} iterations (last change "
                               f"{st.relative_change:.2e}, tolerance {tolerance:g})")
        log.info("BEM σ = %.4g MPa: Δ = %.5g mm, A/A0 = %.4g, %d iterations", s * 1e-6,
                 st.closure * 1e3, st.contact_area_ratio, st.iterations)
        states.append(st)
        if keep_fields or flow:
            pressure.append(p)
            gap.append(g)

    def column(name):
        return np.array([getattr(st, name) for st in states])

    curve = ClosureCurve(stress=stresses, closure=column("closure"), approach=column("approach"),
                        contact_area_ratio=column("contact_area_ratio"),
                        contact_patches=column("contact_patches"),
                        iterations=column("iterations"),
                        complementarity=column("complementarity"),
                        minimum_gap=column("minimum_gap"),
                        plastic_area_ratio=np.zeros(len(states)),
                        mean_flattening=np.zeros(len(states)),
                        composite_modulus=float(composite_modulus),
                        spacing=max(aperture.spacing_x, aperture.spacing_y),
                        shape=(rows, cols), periodic=periodic, tolerance=tolerance,
                        hardness=float(hardness), unloaded_closure=0.0,
                        pressure=pressure, gap=gap, _states=states)
    if profile:
        curve.profile = [st.profile for st in states]
        curve.transform_pair = solver.transform_pair_seconds(5)
        curve.setup_seconds, curve.planning_seconds = solver.setup_seconds, solver.planning_seconds
    return _with_flow(curve, aperture, flow_of, keep_fields) if flow else _fields(curve, keep_fields)


def _fields(curve: ClosureCurve, keep_fields: bool) -> ClosureCurve:
    """The curve without its pressure and gap fields unless they were asked for."""
    if not keep_fields:
        curve.pressure = curve.gap = None
    return curve


def _with_flow(curve: ClosureCurve, aperture: Surface, flow_of: ApertureFlow,
               keep_fields: bool) -> ClosureCurve:
    """The flow columns of `curve` from its gap fields (exactly 0 on each load's contact set, so
    the flow's open fraction is 1 - A/A0), then the fields dropped unless kept."""
    flows = [flow_of(g) for g in curve.gap]
    first = aperture.heights
    first = first - np.nanmin(first)  # the closure's datum: first contact, min e = 0
    tensors = np.array([f.tensor for f in flows])
    curve.transmissivity_xx, curve.transmissivity_yy = tensors[:, 0, 0], tensors[:, 1, 1]
    curve.transmissivity_xy = 0.5 * (tensors[:, 0, 1] + tensors[:, 1, 0])
    curve.hydraulic_aperture = np.array([f.hydraulic_aperture for f in flows])
    curve.mechanical_aperture = np.array([f.mechanical_aperture for f in flows])
    curve.initial_flow, curve.flow_results = flow_of(first), flows
    return _fields(curve, keep_fields)


def _plastic_curve(aperture, composite_modulus, stresses, kernel, hardness, options, keep_fields,
                   periodic, tolerance) -> ClosureCurve:
    """closure_curve for elastic-perfectly-plastic walls (PlasticContact): the stresses are a load
    path; complementarity and patch counts are not computed (NaN)."""
    rows, cols = aperture.shape
    solver = _cpp.PlasticContact(aperture, float(composite_modulus), kernel, hardness, options)
    states, pressure, gap = [], [], []
    for i, s in enumerate(stresses):
        st = solver.solve(float(s))
        if not st.converged:
            raise RuntimeError(f"closure_curve: load {i} (σ = {s:g} Pa) did not converge with "
                               f"hardness {hardness:g} Pa ({st.evaluations} approach trials)")
        log.info("BEM σ = %.4g MPa, H = %.3g GPa: Δ = %.5g mm, A/A0 = %.4g, at H %.3g", s * 1e-6,
                 hardness * 1e-9, st.closure * 1e3, st.contact_area_ratio, st.plastic_area_ratio)
        states.append(st)
        if keep_fields:
            pressure.append(solver.pressure(rows, cols))
            gap.append(solver.gap(rows, cols))
    col = lambda name: np.array([getattr(st, name) for st in states])  # noqa: E731
    nan = np.full(len(states), np.nan)
    return ClosureCurve(stress=stresses, closure=col("closure"), approach=col("approach"),
                        contact_area_ratio=col("contact_area_ratio"), contact_patches=nan,
                        iterations=col("iterations"), complementarity=nan, minimum_gap=nan,
                        plastic_area_ratio=col("plastic_area_ratio"),
                        mean_flattening=col("mean_flattening"),
                        composite_modulus=float(composite_modulus),
                        spacing=max(aperture.spacing_x, aperture.spacing_y), shape=(rows, cols),
                        periodic=periodic, tolerance=tolerance, hardness=hardness,
                        unloaded_closure=solver.unloaded_closure(),
                        pressure=pressure if keep_fields else None,
                        gap=gap if keep_fields else None, _states=states)


def exact_elastic_law(curve: ClosureCurve, residual_stiffness: Optional[float] = None,
                      initial_stiffness: float = 0.0):
    """The exact elastic law of the joint: a monotone C¹ TabulatedLaw through (0, 0) and the
    curve's (Δ, σ) points (PCHIP slopes limited to the Fritsch-Carlson disc, a Hertzian onset
    k(0+) = 0 unless `initial_stiffness` [Pa/m] in [0, σ1/Δ1] seats it: σ changes below the
    first load only), with the exact derivative of that interpolant as tangent. Beyond the last load:
    the table's linear continuation (status validity_limit); below 0: its opening branch with
    `residual_stiffness` [Pa/m] (default 1e-6 σ_max/Δ_max)."""
    rows, cols = curve.shape
    kernel = Kernel.periodic if curve.periodic else Kernel.non_periodic
    return _cpp.exact_elastic_law(curve._states, curve.composite_modulus, curve.spacing,
                                  float(rows), float(cols), kernel, curve.tolerance,
                                  float("nan") if residual_stiffness is None
                                  else float(residual_stiffness), float(initial_stiffness))


# ---- the walls' exact contact as a law of the registry (the planner's rung beside the parametric laws)
#: its key: the exact contact curve of the walls (BEM), tabulated: the planner's rung that is no
#: parametric law (built from the walls by scenes.joint_laws.law_of_walls)
EXACT_CONTACT = "exact_contact"
#: its table's stiffness at zero closure, as a fraction of the secant to its first load σ1/Δ1:
#: the walls' own onset is Hertzian (k(0+) = 0), which leaves a FE model's first linearisation
#: at zero closure without a normal stiffness (a singular Jacobian); 1 % seats it and changes σ
#: below the first load (1/300 of the table's top) only
EXACT_CONTACT_SEATING = 0.01


def _exact_contact(x) -> ClosureLaw:
    """The walls' exact elastic contact (BEM) at x.stresses (law_registry.TopographyInputs), as a
    table (exact_elastic_law)."""
    curve = closure_curve(x.aperture, x.composite_modulus, x.stresses)
    seating = EXACT_CONTACT_SEATING * curve.stress[0] / curve.closure[0]
    return exact_elastic_law(curve, initial_stiffness=seating)


law_registry.register(law_registry.derived_law(
    EXACT_CONTACT, "exact contact of the walls (BEM), tabulated",
    "the walls' exact elastic contact curve (rockjoint.contact, docs/contact.md) as a table",
    _exact_contact, needs="walls"))
