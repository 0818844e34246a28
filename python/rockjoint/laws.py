"""The one law factory: closure laws by name, from a parameter file, or from a topography.

Every law the package builds from a description goes through here: the CLI
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
from typing import Callable, Dict, Mapping, Optional, Sequence, Tuple

import numpy as np

from ._rockjoint.constitutive import (AsperityParameters, BartonBandis, ClosureLaw,
                                      ExponentialLaw, GreenwoodWilliamson, LogarithmicLaw,
                                      TangJiao, TangSubstrate, composite_modulus)

MM = 1e-3          # m per mm
MPA = 1e6          # Pa per MPa
GPA = 1e9          # Pa per GPa
MPA_PER_MM = 1e9   # Pa/m per MPa/mm
PER_MM2 = 1e6      # 1/m² per 1/mm²


@dataclasses.dataclass(frozen=True)
class NamedLaw:
    """A law with the identifier it is registered under and words for people."""

    key: str           # stable identifier, e.g. "tang_jiao" or "greenwood_williamson_empirical"
    label: str         # short display name, e.g. "Tang & Jiao (empirical summits)"
    law: ClosureLaw
    description: str   # what the law is, in one sentence


# ---- the registry of models -------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Model:
    """One model of the registry: its TOML keys (user units) and how it is built (SI)."""

    key: str
    label: str
    description: str
    required: frozenset
    optional: frozenset
    from_values: Callable[[dict], ClosureLaw]   # TOML [law] values (user units) -> law


_ASPERITY_KEYS = frozenset({"composite_modulus_GPa", "young_modulus_GPa", "poisson_ratio",
                            "summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm",
                            "sampling_interval_mm", "height_distribution"})
_STATISTICS_KEYS = frozenset({"summit_density_per_mm2", "summit_radius_mm",
                              "summit_height_std_mm"})
_SUBSTRATE_KEYS = frozenset({"deflection_coefficient", "base_radius_mm"})
_TEXT_KEYS = frozenset({"height_distribution", "variant"})
_ASPERITY_MODELS = ("greenwood_williamson", "tang_substrate", "tang_jiao")


def parameters_from_values(values: Mapping[str, float]) -> AsperityParameters:
    """AsperityParameters (SI) from the TOML [law] keys of an asperity model (user units)."""
    if "composite_modulus_GPa" in values:
        e_star = values["composite_modulus_GPa"] * GPA
    else:
        e_star = composite_modulus(values["young_modulus_GPa"] * GPA, values["poisson_ratio"])
    h = values.get("sampling_interval_mm")
    return AsperityParameters(composite_modulus=e_star,
                              summit_density=values["summit_density_per_mm2"] * PER_MM2,
                              summit_radius=values["summit_radius_mm"] * MM,
                              summit_height_std=values["summit_height_std_mm"] * MM,
                              sampling_interval=None if h is None else h * MM)


def _asperity_from_values(model: str) -> Callable[[dict], ClosureLaw]:
    def build(values: dict) -> ClosureLaw:
        options = {"distribution": values.get("height_distribution", "gaussian")}
        if "deflection_coefficient" in values:
            options["deflection_coefficient"] = values["deflection_coefficient"]
        if "base_radius_mm" in values:
            options["base_radius"] = values["base_radius_mm"] * MM
        if "variant" in values:
            options["variant"] = values["variant"]
        return make_law(model, parameters_from_values(values), **options)
    return build


MODELS: Dict[str, Model] = {m.key: m for m in (
    Model("barton_bandis", "Barton-Bandis", "hyperbolic law σ = K_ni Δ/(1 - Δ/V_m) (theory §6)",
          frozenset({"initial_normal_stiffness_MPa_per_mm", "maximum_closure_mm"}), frozenset(),
          lambda v: BartonBandis(v["initial_normal_stiffness_MPa_per_mm"] * MPA_PER_MM,
                                 v["maximum_closure_mm"] * MM)),
    Model("logarithmic", "logarithmic", "Δ = B ln(σ/σ0) (Swan 1983; theory §6)",
          frozenset({"closure_scale_mm", "seating_stress_MPa"}), frozenset(),
          lambda v: LogarithmicLaw(v["closure_scale_mm"] * MM, v["seating_stress_MPa"] * MPA)),
    Model("exponential", "exponential", "Δ = V_m (1 - exp(-σ/σ_c)) (theory §6)",
          frozenset({"maximum_closure_mm", "characteristic_stress_MPa"}), frozenset(),
          lambda v: ExponentialLaw(v["maximum_closure_mm"] * MM,
                                   v["characteristic_stress_MPa"] * MPA)),
    Model("greenwood_williamson", "GW", "Greenwood-Williamson on the composite topography "
          "(theory §2)", _STATISTICS_KEYS, _ASPERITY_KEYS,
          _asperity_from_values("greenwood_williamson")),
    Model("tang_substrate", "Tang", "GW with Tang's substrate deformation (theory §4)",
          _STATISTICS_KEYS, _ASPERITY_KEYS | _SUBSTRATE_KEYS,
          _asperity_from_values("tang_substrate")),
    Model("tang_jiao", "Tang & Jiao", "Tang & Jiao's interaction cell over Tang's substrate law "
          "(theory §5)", _STATISTICS_KEYS, _ASPERITY_KEYS | _SUBSTRATE_KEYS | {"variant"},
          _asperity_from_values("tang_jiao")),
)}


# ---- by name (SI) -----------------------------------------------------------------------------
def make_law(model: str, parameters: Optional[AsperityParameters] = None, **options) -> ClosureLaw:
    """The law `model` (a key of MODELS) in SI units.

    Asperity models take `parameters` (AsperityParameters) and the options of their classes:
    ``distribution`` ("gaussian", "exponential" or an empirical (heights, radii, area) list, for
    which only the composite modulus of `parameters` is used), ``deflection_coefficient``,
    ``base_radius``, ``reference_separation``, ``seating_stress``, ``tolerance``; "tang_jiao"
    also ``variant``, ``overlap_closure``/``overlap_area_ratio``, ``cell_radius`` /
    ``cell_height_std`` (R and σ of Eq. (1); default β and σ_s of the base), and ``base`` (a
    ready base law, default Tang's substrate law from the same options). Empirical models take their own
    constructor's keywords (e.g. make_law("barton_bandis", initial_normal_stiffness=2e10,
    maximum_closure=3e-4)).
    """
    if model not in MODELS:
        raise ValueError(f"unknown law model {model!r}; expected one of {', '.join(MODELS)}")
    if model not in _ASPERITY_MODELS:
        cls = {"barton_bandis": BartonBandis, "logarithmic": LogarithmicLaw,
               "exponential": ExponentialLaw}[model]
        return cls(**options)
    tang_jiao = {k: options.pop(k) for k in ("variant", "overlap_closure", "overlap_area_ratio",
                                             "cell_radius", "cell_height_std") if k in options}
    base = options.pop("base", None)
    if model != "tang_jiao" and (tang_jiao or base is not None):
        raise ValueError(f"{model}: {', '.join(list(tang_jiao) + ['base'] * (base is not None))} "
                         "apply to tang_jiao only")
    if base is None:
        if parameters is None:
            raise ValueError(f"{model}: AsperityParameters are required")
        empirical = not isinstance(options.get("distribution", "gaussian"), str)
        stats = ({} if empirical else
                 dict(summit_density=parameters.summit_density,
                      summit_radius=parameters.summit_radius,
                      summit_height_std=parameters.summit_height_std))
        cls = GreenwoodWilliamson if model == "greenwood_williamson" else TangSubstrate
        if cls is GreenwoodWilliamson and {"deflection_coefficient", "base_radius"} & options.keys():
            raise ValueError("greenwood_williamson: deflection_coefficient and base_radius "
                             "belong to tang_substrate / tang_jiao")
        base = cls(parameters.composite_modulus, **stats, **options)
    elif options:
        raise ValueError(f"{model}: options {', '.join(options)} describe the base law; "
                         "they cannot be given with base=")
    if model != "tang_jiao":
        return base
    for k in ("overlap_closure", "overlap_area_ratio"):
        if k in tang_jiao:
            tang_jiao[k] = np.asarray(tang_jiao[k], dtype=float)
    # Eq. (1) inputs of the interaction cell: by default R = β and σ_s of the base law; a
    # choice documented in theory §5 lets either be replaced (e.g. the surface rms for σ).
    radius, height_std = tang_jiao.pop("cell_radius", None), tang_jiao.pop("cell_height_std", None)
    if radius is not None or height_std is not None:
        stats = base.asperity_parameters
        tang_jiao.update(composite_modulus=stats.composite_modulus,
                         radius=stats.summit_radius if radius is None else radius,
                         summit_height_std=(stats.summit_height_std if height_std is None
                                            else height_std))
    return TangJiao(base, **tang_jiao)


# ---- from a parameter file ---------------------------------------------------------------------
_TABLE_KEYS = {"maximum_stress_MPa", "maximum_closure_mm", "tolerance",
               "residual_stiffness_MPa_per_mm", "maximum_knots"}


def read_law_file(path: str | os.PathLike) -> Tuple[NamedLaw, dict]:
    """(NamedLaw, tabulation options in SI for rockjoint.tabulate) from a TOML parameter file
    with a [law] section (``model`` = a key of MODELS, keys in the units their names say) and an
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
    if key not in MODELS:
        raise ValueError(f"{path}: [law] model = {key!r}; expected one of "
                         f"{', '.join(sorted(MODELS))}")
    model = MODELS[key]
    missing = sorted(model.required - values.keys())
    if key in _ASPERITY_MODELS and not ("composite_modulus_GPa" in values
                                        or {"young_modulus_GPa", "poisson_ratio"} <= values.keys()):
        missing.append("composite_modulus_GPa (or young_modulus_GPa and poisson_ratio)")
    if missing:
        raise ValueError(f"{path}: [law] model {key} is missing {', '.join(missing)}")
    unknown = sorted(values.keys() - model.required - model.optional)
    if unknown:
        raise ValueError(f"{path}: [law] unknown key(s) {', '.join(unknown)} for model {key}; "
                         f"expected {', '.join(sorted(model.required | model.optional))}")
    for k, v in values.items():
        if k not in _TEXT_KEYS and (isinstance(v, bool) or not isinstance(v, (int, float))):
            raise ValueError(f"{path}: [law] {k} = {v!r} must be a number")
    try:
        law = model.from_values(values)
    except TypeError as err:
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
    options = {"tolerance": float(table.get("tolerance", 1e-6)),
               "maximum_knots": int(table.get("maximum_knots", 20000))}
    if "maximum_stress_MPa" in table:
        options["max_stress"] = float(table["maximum_stress_MPa"]) * MPA
    else:
        options["max_closure"] = float(table["maximum_closure_mm"]) * MM
    if "residual_stiffness_MPa_per_mm" in table:
        options["residual_stiffness"] = float(table["residual_stiffness_MPa_per_mm"]) * MPA_PER_MM
    return options


# ---- from a topography -------------------------------------------------------------------------
#: The law recommended for a joint described by its topography, and why. Evidence:
#: bench/results/accuracy_ladder.md (every law against the exact elastic contact, BEM, of
#: the same walls on the project's synthetic granite-like and sandstone-like joints).
RECOMMENDED = "tang_jiao_i2_gw"
RECOMMENDATION = (
    "Tang & Jiao I2 over GW, seated at the measured first contact: of every law rockjoint offers "
    "it has the smallest mean closure error against exact elastic contact (BEM) of the same "
    "walls on the project's synthetic joints (loads 1-30 MPa: sandstone-like 1.9 %, increment "
    "-4.4 %; granite-like 7.3 %, increment -12.9 %), at ~7 µs per evaluation "
    "(bench/results/accuracy_ladder.md). It misses the 3 % target on well-mated joints.")


def first_contact_separation(summits, parameters: AsperityParameters,
                             distribution: str = "gaussian") -> float:
    """Seating datum d0 [m] of a parametric law at the measured first contact: the highest
    summit of `summits` (a topography.TopographyAnalysis) above the mean summit height, in the
    law's height frame (Gaussian heights: mean summit at 0; exponential: at σ_s)."""
    z = np.asarray(summits.summits["heights"], dtype=float)
    if z.size < 2:
        raise ValueError(f"{z.size} summit(s): no first-contact datum")
    mean_in_frame = parameters.summit_height_std if distribution == "exponential" else 0.0
    return float(z.max() - z.mean()) + mean_in_frame


def laws_from_topography(parameters: AsperityParameters, *, summits=None,
                         seating: str = "first_contact", empirical: bool = True,
                         overlap: Optional[Tuple[Sequence[float], Sequence[float]]] = None,
                         distribution: str = "gaussian", variant: str = "I1",
                         **substrate) -> Dict[str, NamedLaw]:
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
    laws: Dict[str, NamedLaw] = {}

    def add(key, label, description, law):
        laws[key] = NamedLaw(key, label, law, description)

    def family(suffix: str, label_suffix: str, options: dict):
        gw = make_law("greenwood_williamson", parameters, **options)
        tang = make_law("tang_substrate", parameters, **options, **substrate)
        add("greenwood_williamson" + suffix, "GW" + label_suffix, MODELS["greenwood_williamson"]
            .description, gw)
        add("tang_substrate" + suffix, "Tang" + label_suffix, MODELS["tang_substrate"].description,
            tang)
        add("tang_jiao" + suffix, "Tang & Jiao" + label_suffix, MODELS["tang_jiao"].description,
            make_law("tang_jiao", base=tang, variant=variant))
        return gw, tang

    gw, _ = family("", "", dict(distribution=distribution, **seat))
    add(RECOMMENDED, "Tang & Jiao I2 over GW (recommended)", RECOMMENDATION,
        make_law("tang_jiao", base=gw, variant="I2"))
    if summits is not None and empirical:
        from .topography import empirical_summits
        _, tang = family("_empirical", " (empirical summits)",
                         dict(distribution=empirical_summits(summits)))
        if overlap is not None:
            closure, ratio = overlap
            add("tang_jiao_empirical_geometric", "Tang & Jiao (empirical, geometric area)",
                "Tang & Jiao over the empirical Tang law with the geometric overlap ratio "
                "fraction{e <= Δ} in Eq. (2) (theory §3, §5)",
                make_law("tang_jiao", base=tang, variant=variant, overlap_closure=closure,
                         overlap_area_ratio=ratio))
    return laws


def describe_models() -> str:
    """One line per registered model: key, what it is, its TOML keys."""
    lines = []
    for m in MODELS.values():
        optional = sorted(m.optional - m.required)
        lines.append(f"{m.key}: {m.description}; requires {', '.join(sorted(m.required))}"
                     + (f"; optional {', '.join(optional)}" if optional else ""))
    return "\n".join(lines)

