# SPDX-License-Identifier: MIT
"""The one law factory: closure laws by name, from a parameter file, or from a topography.

Every law the package builds from a description goes through here (the laws themselves are the
records of rockjoint.law_registry, their one place): the CLI
(``python3 -m rockjoint tabulate``, ``topography analyse``), the TOML parameter files, the
topography code and the demos. Roughness statistics travel as one type,
:class:`rockjoint.AsperityParameters` (E*, η, β, σ_s and the sampling interval h they belong
to); laws come back as :class:`NamedLaw` objects keyed by stable model identifiers, never by
display strings. Defaults (κ_s, r0, the seating reference, the quadrature tolerance) are the C++
laws' own: nothing here repeats them.

SI units in the Python API (Pa, m); the TOML files use MPa, mm and GPa, named in every key.
"""
from __future__ import annotations

import dataclasses
import os
import tomllib
from typing import Dict, Optional, Sequence, Tuple

import numpy as np

from ._rockjoint.constitutive import AsperityParameters, ClosureLaw
from . import law_registry
from . import contact  # noqa: F401  (registers the walls' exact contact, beside its BEM solver)
from .law_registry import MM, MPA, MPA_PER_MM, get, parametric_laws, topography_laws
from .tabulation import DEFAULT_MAXIMUM_KNOTS, DEFAULT_TOLERANCE
from .topography import empirical_summits


@dataclasses.dataclass(frozen=True)
class NamedLaw:
    """A law with the identifier it is registered under and words for people."""

    key: str           # stable identifier, e.g. "tang_jiao" or "greenwood_williamson_empirical"
    label: str         # short display name, e.g. "Tang & Jiao (empirical summits)"
    law: ClosureLaw
    description: str   # what the law is, in one sentence


_TEXT_KEYS = frozenset({"height_distribution", "variant", "virgin"})


# ---- by name (SI) -----------------------------------------------------------------------------
def make_law(model: str, parameters: Optional[AsperityParameters] = None, **options) -> ClosureLaw:
    """The law `model` (a key of the law registry, rockjoint.law_registry) in SI units.

    Asperity models take `parameters` (AsperityParameters) and the options of their classes:
    ``distribution`` ("gaussian", "exponential" or an empirical (heights, radii, area) list, for
    which only the composite modulus of `parameters` is used), ``deflection_coefficient``,
    ``base_radius``, ``reference_separation``, ``seating_stress``, ``tolerance``; "tang_jiao"
    also ``variant``, ``overlap_closure``/``overlap_area_ratio``, ``cell_radius`` /
    ``cell_height_std`` (R and σ of Eq. (1); default β and σ_s of the base), and ``base`` (a
    ready base law, default Tang's substrate law from the same options). Laws with their own
    parameters take them as SI keywords (e.g. make_law("barton_bandis",
    initial_normal_stiffness=2e10, maximum_closure=3e-4)).

    The Barton-Bandis hyperbola σ = K_ni Δ / (1 - Δ/V_m): at Δ = V_m/3 the stress is
    1.5 K_ni Δ, 3 MPa here, and the stiffness K_ni / (1 - Δ/V_m)² = 2.25 K_ni:

    >>> law = make_law("barton_bandis", initial_normal_stiffness=2e10, maximum_closure=3e-4)
    >>> round(float(law.normal_stress(1e-4)) / 1e6, 9)   # [MPa]
    3.0
    >>> round(float(law.normal_stiffness(1e-4)) / 2e10, 9)   # [K_ni]
    2.25
    >>> round(float(law.closure_at_stress(3e6)) * 1e3, 9)   # the inverse [mm]
    0.1
    """
    return get(model).build(parameters, **options)


# ---- from a parameter file ---------------------------------------------------------------------
_TABLE_KEYS = {"maximum_stress_MPa", "maximum_closure_mm", "tolerance",
               "residual_stiffness_MPa_per_mm", "maximum_knots"}


def read_law_file(path: str | os.PathLike) -> Tuple[NamedLaw, dict]:
    """(NamedLaw, tabulation options in SI for rockjoint.tabulate) from a TOML parameter file
    with a [law] section (``model`` = a key of the law registry, keys in the units their names say) and an
    optional [table] section. ValueError naming the file and the key for every mistake."""
    path = os.fspath(path)
    with open(path, "rb") as f:
        try:
            doc = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise ValueError(f"{path}: not valid TOML: {err}") from err
    for section in doc:
        if section not in ("law", "table"):
            raise ValueError(f"{path}: unknown section [{section}]; expected [law] and [table]")
    values = dict(doc.get("law", {}))
    key = values.pop("model", None)
    laws = parametric_laws()
    if key not in laws:
        raise ValueError(f"{path}: [law] model = {key!r}; expected one of "
                         f"{', '.join(sorted(laws))}")
    model = laws[key]
    required, optional, asperity = model.file_required, model.file_optional, model.asperity
    if model.history:   # the history's keys beside its virgin law's own
        virgin = laws.get(values.get("virgin"))
        if virgin is None or virgin.history:
            raise ValueError(f"{path}: [law] virgin = {values.get('virgin')!r}; expected one of "
                             f"{', '.join(sorted(k for k, r in laws.items() if not r.history))}")
        required, optional = required | virgin.file_required, optional | virgin.file_optional
        asperity = virgin.asperity
    missing = sorted(required - values.keys())
    if asperity and not ("composite_modulus_GPa" in values
                         or {"young_modulus_GPa", "poisson_ratio"} <= values.keys()):
        missing.append("composite_modulus_GPa (or young_modulus_GPa and poisson_ratio)")
    if missing:
        raise ValueError(f"{path}: [law] model {key} is missing {', '.join(missing)}")
    unknown = sorted(values.keys() - required - optional)
    if unknown:
        raise ValueError(f"{path}: [law] unknown key(s) {', '.join(unknown)} for model {key}; "
                         f"expected {', '.join(sorted(required | optional))}")
    for k, v in values.items():
        if k not in _TEXT_KEYS and (isinstance(v, bool) or not isinstance(v, (int, float))):
            raise ValueError(f"{path}: [law] {k} = {v!r} must be a number")
    # the one range check of a law's parameters (law_registry.Quantity.problem, the C++ law's ranges)
    for q in model.quantities() + (virgin.quantities() if model.history else ()):
        problem = q.problem(values[q.file_key] * q.scale)
        if problem:
            raise ValueError(f"{path}: [law] {q.file_key} = {values[q.file_key]!r} is out of range: "
                             f"{q.symbol} {problem} ({q.unit} in the file)")
    try:
        law = model.from_file_values(values)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{path}: [law] model {key}: {err}") from err
    return NamedLaw(key, model.label, law, model.description), _table_options(path, doc)


def _table_options(path: str, doc: dict) -> dict:
    table = dict(doc.get("table", {}))
    unknown = sorted(table.keys() - _TABLE_KEYS)
    if unknown:
        raise ValueError(f"{path}: [table] unknown key(s) {', '.join(unknown)}; expected "
                         f"{', '.join(sorted(_TABLE_KEYS))}")
    if ("maximum_stress_MPa" in table) == ("maximum_closure_mm" in table):
        raise ValueError(f"{path}: [table] needs exactly one of maximum_stress_MPa or "
                         "maximum_closure_mm")
    options = {"tolerance": float(table.get("tolerance", DEFAULT_TOLERANCE)),
               "maximum_knots": int(table.get("maximum_knots", DEFAULT_MAXIMUM_KNOTS))}
    if "maximum_stress_MPa" in table:
        options["max_stress"] = float(table["maximum_stress_MPa"]) * MPA
    else:
        options["max_closure"] = float(table["maximum_closure_mm"]) * MM
    if "residual_stiffness_MPa_per_mm" in table:
        options["residual_stiffness"] = float(table["residual_stiffness_MPa_per_mm"]) * MPA_PER_MM
    return options


# ---- from a topography -------------------------------------------------------------------------
#: the law recommended for a joint described by its topography, and why (law_registry: its record)
RECOMMENDED, RECOMMENDATION = law_registry.RECOMMENDED, law_registry.RECOMMENDATION


def first_contact_separation(summits, parameters: AsperityParameters,
                             distribution: str = "gaussian") -> float:
    """Seating datum d0 [m] of a parametric law at the measured first contact: the highest
    summit of `summits` (a topography.TopographyAnalysis) above the mean summit height, in the
    law's height frame (Gaussian heights: mean summit at 0; exponential: at σ_s)."""
    z = np.asarray(summits.summits["heights"], dtype=float)
    if z.size < 2:
        raise ValueError(f"{z.size} summit(s): no first-contact datum")
    # the frames of law_registry.HEIGHT_DISTRIBUTIONS: Gaussian heights around 0, exponential from 0
    gaussian, _ = law_registry.HEIGHT_DISTRIBUTIONS
    mean_in_frame = 0.0 if distribution == gaussian else parameters.summit_height_std
    return float(z.max() - z.mean()) + mean_in_frame


def laws_from_topography(parameters: AsperityParameters, *, summits=None,
                         seating: str = "first_contact", empirical: bool = True,
                         overlap: Optional[Tuple[Sequence[float], Sequence[float]]] = None,
                         distribution: str = "gaussian", variant: str = "I1",
                         keys: Optional[Sequence[str]] = None, **substrate) -> Dict[str, NamedLaw]:
    """The asperity laws of one joint from its measured statistics, keyed by identifier:

    - "greenwood_williamson", "tang_substrate", "tang_jiao" (`variant` over Tang; elastic area
      in Eq. (2)) on the parametric height `distribution`, and RECOMMENDED =
      "tang_jiao_i2_gw" (I2 over GW), all seated by `seating`: "first_contact" (default: the
      measured highest summit, needs `summits`; the BEM datum, see RECOMMENDATION) or
      "mean+3.5" (mean summit height + 3.5 σ_s, the laws' own default);
    - with `summits` (a topography.TopographyAnalysis) and `empirical`: GW, Tang and Tang &
      Jiao over the measured summit list, keys with suffix "_empirical" (each summit its own
      radius, seated at the highest);
    - with `summits` and `overlap` (topography.overlap_curve(joint.aperture)):
      "tang_jiao_empirical_geometric", whose Eq. (2) uses fraction{e <= Δ}.

    `keys`: only these laws (and what they are built on) are built; default all.
    `substrate`: deflection_coefficient, base_radius (the laws' defaults unless given).
    """
    unknown = set(substrate) - {"deflection_coefficient", "base_radius"}
    if unknown:
        raise ValueError(f"laws_from_topography: unknown option(s) {', '.join(sorted(unknown))}")
    if overlap is not None and summits is None:
        raise ValueError("overlap: the geometric overlap curve is measured from first contact; "
                         "give summits= too (the empirical laws share that datum)")
    if seating == "first_contact":
        if summits is None:
            raise ValueError("seating='first_contact' needs summits= (the analysed topography "
                             "gives the highest summit); or pass seating='mean+3.5'")
        seat = {"reference_separation": first_contact_separation(summits, parameters,
                                                                 distribution)}
    elif seating == "mean+3.5":
        seat = {}
    else:
        raise ValueError(f"seating {seating!r}: expected 'first_contact' or 'mean+3.5'")
    inputs = law_registry.TopographyInputs(
        parameters, seat, distribution, variant, substrate,
        summits=empirical_summits(summits) if summits is not None and empirical else None,
        overlap=overlap)
    available = {"statistics": True, "summits": inputs.summits is not None,
                 "overlap": inputs.summits is not None and overlap is not None, "walls": False}
    return {r.key: NamedLaw(r.key, r.label, inputs.law(r.key), r.description)
            for r in topography_laws().values() if available[r.needs] and (keys is None or r.key in keys)}


def describe_models() -> str:
    """One line per registered model: key, what it is, its parameter-file keys."""
    lines = []
    for m in parametric_laws().values():
        optional = sorted(m.file_optional - m.file_required)
        lines.append(f"{m.key}: {m.description}; requires {', '.join(sorted(m.file_required))}"
                     + (f"; optional {', '.join(optional)}" if optional else ""))
    return "\n".join(lines)

