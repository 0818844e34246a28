# SPDX-License-Identifier: MIT
"""The law registry: the one place where a closure law's identity lives.

Each law rockjoint builds has one `LawRecord`: its key (a C++ law's ``name()``), words for
people, its SI builder from its own parameters, those parameters (`Quantity`: keyword, symbol,
unit and admissible range, read from the C++ law's own metadata, ``<Law>.parameter_specs()``),
their parameter-file keys, what a calibration fits, its history, and how it is derived from a
topography (`TopographyInputs`: the statistics, the measured summits or the walls). A law derived
from a topography only (Tang & Jiao I2 over GW, the laws on measured summits, the walls' exact
contact, which contact.py registers beside the BEM) is a record too, without a parameter builder.
Everything that names laws reads from here: ``laws.make_law`` and ``laws.read_law_file`` (TOML),
``laws.laws_from_topography``, ``calibration.calibrate``, the scenes' law sections, the CLI's
choices (``python3 -m rockjoint tabulate | calibrate``) and the docs table (``docs_table``); the
one range check of a law's parameters is `Quantity.problem`. A table (.rjt) keeps its source's key
(``TabulatedLaw.source_model``) and any FE joint takes any law, so a registered law is usable end
to end. Adding a law: docs/architecture.md.

Laws can also be registered from outside the package: modules named in the environment variable
``ROCKJOINT_LAWS`` (comma separated) or in the entry-point group ``rockjoint.laws`` are imported
by ``load_plugins()`` (the CLI calls it), and call ``register``.

Units: SI in every builder; the files and reports use the units the quantities name (mm, MPa,
GPa, MPa/mm, 1/mm²), converted here and nowhere else.
"""
from __future__ import annotations

import dataclasses
import importlib
import math
import os
from importlib.metadata import entry_points
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from .units import DIMENSIONS, LAW_UNIT_DIMENSION
from ._rockjoint.constitutive import (AsperityParameters, BartonBandis, ClosureLaw,
                                      ExponentialLaw, GreenwoodWilliamson, LogarithmicLaw,
                                      NormalHysteresis, ParameterSpec, TangJiao, TangSubstrate,
                                      composite_modulus)

#: SI per user unit, for files and reports: entries of rockjoint.units (the one unit table)
UNITS = {unit: DIMENSIONS[dimension][unit] for unit, dimension in LAW_UNIT_DIMENSION.items()}
MM, MPA, GPA, MPA_PER_MM, PER_MM2 = (UNITS[u] for u in ("mm", "MPa", "GPa", "MPa/mm", "1/mm²"))
_FILE_SUFFIX = {"-": "", "mm": "_mm", "MPa": "_MPa", "GPa": "_GPa", "MPa/mm": "_MPa_per_mm",
                "1/mm²": "_per_mm2"}


@dataclasses.dataclass(frozen=True)
class Quantity:
    """A law parameter: its SI keyword, symbol, user unit (files, reports) and admissible range:
    the C++ law's own (`spec`, its ParameterSpec: `Quantity.of`), or finite and > 0 for a
    parameter of a law composed in Python without C++ metadata."""

    name: str
    symbol: str
    unit: str
    spec: Optional[ParameterSpec] = dataclasses.field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if self.unit not in UNITS:
            raise ValueError(f"Quantity {self.name!r}: unit {self.unit!r} unknown; one of {sorted(UNITS)}")

    @classmethod
    def of(cls, spec: ParameterSpec) -> "Quantity":
        """The quantity a C++ law's ParameterSpec describes (its file unit, its range)."""
        return cls(spec.name, spec.symbol, spec.file_unit, spec)

    @property
    def range(self) -> str:
        """The admissible range in words (SI), e.g. 'finite and > 0', 'in [0, 1)'."""
        return self.spec.range if self.spec is not None else "finite and > 0"

    def problem(self, value: float) -> Optional[str]:
        """None if `value` [SI] is admissible, else what is wrong ('must be ...'): the one range
        check of a law parameter (parameter files, scenes, calibration)."""
        ok = self.spec.admits(float(value)) if self.spec is not None else math.isfinite(value) and value > 0
        return None if ok else f"must be {self.range}"

    @property
    def scale(self) -> float:
        """SI per user unit."""
        return UNITS[self.unit]

    @property
    def file_key(self) -> str:
        """The key in a parameter file, its unit in its name (e.g. maximum_closure_mm)."""
        return self.name + _FILE_SUFFIX[self.unit]


def quantities(cls, names: Optional[Sequence[str]] = None) -> Tuple[Quantity, ...]:
    """The Quantities of a C++ class's parameter_specs() (all, or those `names`, in that order)."""
    specs = {s.name: s for s in cls.parameter_specs()}
    return tuple(Quantity.of(specs[n]) for n in (names or specs))


#: the summit statistics an asperity law is built from (E* comes from the rock or the file)
ASPERITY_STATISTICS = quantities(AsperityParameters, ("summit_density", "summit_radius", "summit_height_std"))
#: the history's own parameters (docs/hysteresis.md, H1-H2), beside its virgin law's
HISTORY_PARAMETERS = quantities(NormalHysteresis)


@dataclasses.dataclass(frozen=True)
class CalibrationSpec:
    """What `calibration.calibrate` fits: `unknowns` (positive, fitted as logarithms), the given
    inputs `needs` (Quantities the caller must pass, SI) and `options` (optional SI keywords), the builder
    (values SI, given) -> law, the starting values initial_guess(stress, closure, given, build,
    offset, closure_of) -> values SI (+ the closure offset when `offset`; closure_of(law,
    stresses) -> closures), and whether a closure offset is fitted by default."""

    unknowns: Tuple[Quantity, ...]
    build: Callable[[Sequence[float], dict], ClosureLaw]
    initial_guess: Callable[..., list]
    needs: Tuple[Quantity, ...] = ()
    options: Tuple[str, ...] = ()
    fit_offset: bool = False


@dataclasses.dataclass(frozen=True)
class LawRecord:
    """One law of the registry: built from its own parameters (`build`, the file keys, a
    calibration), derived from a topography (`topography`), or both."""

    key: str                 # stable identifier (for a C++ law class: its name())
    label: str               # short display name
    description: str         # what the law is, in one sentence (with its theory section)
    build: Optional[Callable[..., ClosureLaw]]  # build(parameters=None, **SI options); None: topography only
    file_required: frozenset                    # parameter-file keys (user units)
    file_optional: frozenset
    from_file_values: Optional[Callable[[dict], ClosureLaw]]
    calibration: Optional[CalibrationSpec] = None
    parameters: Tuple[Quantity, ...] = ()       # SI keywords of a law built from its own values
    asperity: bool = False                      # built from AsperityParameters (E*, η, β, σ_s)
    # a law with history over a virgin law (named by the key `virgin`, built from its own values
    # and options): `parameters` are then the history's own, beside the virgin law's
    history: bool = False
    #: the law derived from a joint's topography: TopographyInputs -> law (None: not derived)
    topography: Optional[Callable[["TopographyInputs"], ClosureLaw]] = None
    #: what the derivation needs: "statistics"; "summits" (the measured summit list); "overlap"
    #: (that and the overlap curve); "walls" (the walls themselves, built outside
    #: laws_from_topography)
    needs: str = "statistics"
    #: its row of the accuracy ladder (bench/results/accuracy_ladder.json; None: not on it)
    ladder_row: Optional[str] = None

    @property
    def parametric(self) -> bool:
        """Built from its own parameters (a model of make_law, parameter files and scenes)."""
        return self.build is not None

    def quantities(self) -> Tuple[Quantity, ...]:
        """The parameters a user gives this law (SI keywords; for a law with history, the
        history's own, beside its virgin law's)."""
        return ASPERITY_STATISTICS if self.asperity else self.parameters


REGISTRY: Dict[str, LawRecord] = {}


def register(record: LawRecord) -> LawRecord:
    """Add a law to the registry (ValueError for a key already taken or a malformed record)."""
    if not isinstance(record, LawRecord):
        raise ValueError(f"register: a LawRecord is needed, got {type(record).__name__}")
    if not record.key.isidentifier() or record.key != record.key.lower():
        raise ValueError(f"register: law key {record.key!r} must be a lower-case identifier")
    if record.key in REGISTRY:
        raise ValueError(f"register: a law {record.key!r} is registered already")
    if record.build is None and record.topography is None:
        raise ValueError(f"register: law {record.key!r} has neither a builder nor a topography derivation")
    if record.needs not in ("statistics", "summits", "overlap", "walls"):
        raise ValueError(f"register: law {record.key!r}: needs = {record.needs!r}")
    REGISTRY[record.key] = record
    return record


def parametric_laws() -> Dict[str, LawRecord]:
    """{key: record} of the laws built from their own parameters (make_law, files, scenes)."""
    return {k: r for k, r in REGISTRY.items() if r.parametric}


def topography_laws() -> Dict[str, LawRecord]:
    """{key: record} of the laws derived from a topography (laws_from_topography, the ladder)."""
    return {k: r for k, r in REGISTRY.items() if r.topography is not None}


def unregister(key: str) -> None:
    """Remove a law (tests, plugins being reloaded)."""
    REGISTRY.pop(key, None)


def get(key: str) -> LawRecord:
    """The record of the law built from its parameters named `key`, or ValueError listing them."""
    laws = parametric_laws()
    if key not in laws:
        raise ValueError(f"unknown law model {key!r}; expected one of {', '.join(sorted(laws))}")
    return laws[key]


def calibratable() -> list:
    """Keys of the laws `calibrate` can fit."""
    return sorted(k for k, r in REGISTRY.items() if r.calibration is not None)


def load_plugins() -> list:
    """Import the law plugins named in ROCKJOINT_LAWS and the entry points 'rockjoint.laws';
    returns the module names loaded. An import error names the plugin."""
    loaded = []
    names = [n.strip() for n in os.environ.get("ROCKJOINT_LAWS", "").split(",") if n.strip()]
    for name in names:
        try:
            importlib.import_module(name)
        except ImportError as err:
            raise ValueError(f"ROCKJOINT_LAWS: cannot import law plugin {name!r}: {err}") from err
        loaded.append(name)
    for ep in entry_points(group="rockjoint.laws"):
        ep.load()
        loaded.append(ep.value)
    return loaded


def docs_table() -> str:
    """The registered laws as a Markdown table (key, law, parameter-file keys, fitted by
    `calibrate`)."""
    rows = ["| key | law | parameter-file keys | fitted by `calibrate` |", "|---|---|---|---|"]
    for r in parametric_laws().values():
        keys = ", ".join(f"`{k}`" for k in sorted(r.file_required))
        if r.history:
            keys += ", and the virgin law's keys"
        if r.asperity:
            keys += ", `composite_modulus_GPa` (or `young_modulus_GPa`, `poisson_ratio`)"
        fitted = ", ".join(q.symbol for q in r.calibration.unknowns) if r.calibration else "-"
        if r.history:
            fitted = ", ".join(q.symbol for q in r.parameters) + " and the virgin law's (`--cycles`)"
        rows.append(f"| `{r.key}` | {r.description} | {keys} | {fitted} |")
    return "\n".join(rows)


# ---- laws built from their own parameters ------------------------------------------------------
def law_from_parameters(key: str, label: str, description: str, make: Callable[..., ClosureLaw],
                        parameters: Sequence[Quantity], initial_guess=None) -> LawRecord:
    """A record for a law built by `make(**SI parameters)` (a law class, or a function that
    composes one): the builder, the parameter-file keys and, with `initial_guess`, a calibration
    of every parameter."""
    parameters = tuple(parameters)
    names = [q.name for q in parameters]

    def build(parameters_=None, **options) -> ClosureLaw:
        if parameters_ is not None:
            raise ValueError(f"{key}: takes its own parameters ({', '.join(names)}), not AsperityParameters")
        unknown = sorted(set(options) - set(names))
        if unknown:
            raise ValueError(f"{key}: unknown parameter(s) {', '.join(unknown)}; expected {', '.join(names)}")
        return make(**options)

    def from_file(values: dict) -> ClosureLaw:
        return make(**{q.name: values[q.file_key] * q.scale for q in parameters})

    calibration = None
    if initial_guess is not None:
        calibration = CalibrationSpec(parameters, lambda v, g: make(**dict(zip(names, v))), initial_guess)
    return LawRecord(key, label, description, build, frozenset(q.file_key for q in parameters),
                     frozenset(), from_file, calibration, parameters)


def _barton_bandis_guess(s, d, given, build, offset, closure_of) -> list:
    """σ/Δ = K_ni + σ/V_m is linear in σ (theory §6); an offset starts at 0."""
    pos = (d > 0) & (s > 0)
    slope, intercept = np.polyfit(s[pos], s[pos] / d[pos], 1) if pos.sum() >= 2 else (0.0, 0.0)
    k = intercept if intercept > 0 else float(np.median(s[pos] / d[pos]))
    v = 1.0 / slope if slope > 0 and 1.0 / slope > d[-1] else 1.5 * d[-1]
    return [k, v] + ([0.0] if offset else [])


def _exponential_guess(s, d, given, build, offset, closure_of) -> list:
    pos = (d > 0) & (s > 0)
    v = 1.2 * d[-1]
    return [v, float(np.median(-s[pos] / np.log1p(-d[pos] / v)))] + ([0.0] if offset else [])


# their parameters, units and ranges: the C++ classes' own (parameter_specs)
register(law_from_parameters(
    "barton_bandis", "Barton-Bandis", "hyperbolic law σ = K_ni Δ/(1 - Δ/V_m) (theory §6)",
    BartonBandis, quantities(BartonBandis), _barton_bandis_guess))
register(law_from_parameters(
    "logarithmic", "logarithmic", "Δ = B ln(σ/σ0) (Swan 1983; theory §6)", LogarithmicLaw,
    quantities(LogarithmicLaw)))
register(law_from_parameters(
    "exponential", "exponential", "Δ = V_m (1 - exp(-σ/σ_c)) (theory §6)", ExponentialLaw,
    quantities(ExponentialLaw), _exponential_guess))


# ---- asperity laws: built from the statistics of the composite topography -----------------------
_ASPERITY_KEYS = frozenset({"composite_modulus_GPa", "young_modulus_GPa", "poisson_ratio",
                            "summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm",
                            "sampling_interval_mm", "height_distribution"})
_STATISTICS_KEYS = frozenset({"summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm"})
_SUBSTRATE_KEYS = frozenset({"deflection_coefficient", "base_radius_mm"})
#: laws Tang & Jiao's interaction cell can sit on (calibrate(base=...), the CLI's --base)
TANG_JIAO_BASES = ("tang_substrate", "greenwood_williamson")
#: the base law of tang_jiao unless one is named (calibrate, the CLI's --base)
DEFAULT_TANG_JIAO_BASE = TANG_JIAO_BASES[0]
#: summit-height distributions of the parametric asperity laws
HEIGHT_DISTRIBUTIONS = ("gaussian", "exponential")
_TANG_JIAO_OPTIONS = ("variant", "overlap_closure", "overlap_area_ratio", "cell_radius", "cell_height_std")


def parameters_from_values(values) -> AsperityParameters:
    """AsperityParameters (SI) from the parameter-file keys of an asperity model (user units)."""
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


def _summit_law_build(key: str, cls, substrate: bool) -> Callable[..., ClosureLaw]:
    """The SI builder of a summit-population law `cls` (GW, or Tang's with `substrate` options
    deflection_coefficient / base_radius); options: laws.make_law's docstring."""

    def build(parameters: Optional[AsperityParameters] = None, **options) -> ClosureLaw:
        extra = sorted(set(options) & (set(_TANG_JIAO_OPTIONS) | {"base"}))
        if extra:
            raise ValueError(f"{key}: {', '.join(extra)} apply to tang_jiao only")
        if not substrate and {"deflection_coefficient", "base_radius"} & options.keys():
            raise ValueError(f"{key}: deflection_coefficient and base_radius "
                             "belong to tang_substrate / tang_jiao")
        if parameters is None:
            raise ValueError(f"{key}: AsperityParameters are required")
        empirical = not isinstance(options.get("distribution", "gaussian"), str)
        stats = ({} if empirical else
                 dict(summit_density=parameters.summit_density, summit_radius=parameters.summit_radius,
                      summit_height_std=parameters.summit_height_std))
        return cls(parameters.composite_modulus, **stats, **options)

    return build


def _tang_jiao_build(default_base: Callable[..., ClosureLaw]) -> Callable[..., ClosureLaw]:
    """The SI builder of Tang & Jiao's cell over `base=` (a ready law) or, by default, the law
    `default_base(parameters, **options)` (options: laws.make_law's docstring)."""

    def build(parameters: Optional[AsperityParameters] = None, **options) -> ClosureLaw:
        tang_jiao = {k: options.pop(k) for k in _TANG_JIAO_OPTIONS if k in options}
        base = options.pop("base", None)
        if base is None and parameters is None:  # named for the law the user asked for
            raise ValueError(f"tang_jiao: AsperityParameters are required (for its base law, "
                             f"{DEFAULT_TANG_JIAO_BASE} by default), or base= a ready closure law")
        if base is None:
            base = default_base(parameters, **options)
        elif options:
            raise ValueError(f"tang_jiao: options {', '.join(options)} describe the base law; "
                             "they cannot be given with base=")
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

    return build


_GW_BUILD = _summit_law_build("greenwood_williamson", GreenwoodWilliamson, substrate=False)
_TANG_BUILD = _summit_law_build("tang_substrate", TangSubstrate, substrate=True)
_TANG_JIAO_BUILD = _tang_jiao_build(_TANG_BUILD)


def _asperity_from_file(build: Callable[..., ClosureLaw]) -> Callable[[dict], ClosureLaw]:
    def from_file(values: dict) -> ClosureLaw:
        options = {"distribution": values.get("height_distribution", "gaussian")}
        if "deflection_coefficient" in values:
            options["deflection_coefficient"] = values["deflection_coefficient"]
        if "base_radius_mm" in values:
            options["base_radius"] = values["base_radius_mm"] * MM
        if "variant" in values:
            options["variant"] = values["variant"]
        return build(parameters_from_values(values), **options)

    return from_file


def _gw_type(tang_jiao: bool) -> Callable[[Sequence[float], dict], ClosureLaw]:
    """(η, σ_s) fitted, E* and β given: GW, or (`tang_jiao`) Tang & Jiao over the given base."""
    def build(values, given) -> ClosureLaw:
        eta, sigma_s = values
        stats = AsperityParameters(composite_modulus=given["composite_modulus"], summit_density=eta,
                                   summit_radius=given["summit_radius"], summit_height_std=sigma_s)
        distribution = given.get("distribution", "gaussian")
        if not tang_jiao:
            return _GW_BUILD(stats, distribution=distribution)
        base = given.get("base", DEFAULT_TANG_JIAO_BASE)
        substrate = base == "tang_substrate"   # Tang's substrate options (the base radius)
        kw = {} if given.get("base_radius") is None or not substrate else {"base_radius": given["base_radius"]}
        return _TANG_JIAO_BUILD(stats, base=get(base).build(stats, distribution=distribution, **kw),
                                variant=given.get("variant", "I1"))
    return build


def _gw_type_guess(s, d, given, build, offset, closure_of) -> list:
    """σ_s from the slope of Δ against ln σ (exact for exponential heights), then η so that the
    law carries the middle stress at the middle closure (σ ∝ η for GW), with the offset."""
    pos = (d > 0) & (s > 0)
    upper = pos & (s >= np.median(s[pos]))
    sigma_s = float(np.polyfit(np.log(s[upper]), d[upper], 1)[0]) if upper.sum() >= 2 else 0.0
    sigma_s = max(sigma_s, 0.05 * (d[-1] - d[0]))
    eta, c = 1e5, 0.0
    mid = int(np.argmin(np.abs(s - np.median(s))))
    for _ in range(4):
        law = build([eta, sigma_s], given)
        target = d[mid] + c
        if target > 0:
            eta *= s[mid] / float(law.normal_stress(target))
        if offset:
            law = build([eta, sigma_s], given)
            c = float(closure_of(law, s[:1])[0]) - d[0]
    return [eta, sigma_s] + ([c] if offset else [])


_ETA, _, _SIGMA_S = ASPERITY_STATISTICS
#: what a GW-type calibration is given: E* and β, with the C++ AsperityParameters' units and ranges
_GIVEN = quantities(AsperityParameters, ("composite_modulus", "summit_radius"))


# ---- laws derived from a topography (laws.laws_from_topography, the planner's rungs) ------------
@dataclasses.dataclass
class TopographyInputs:
    """What a law derived from a topography is built from: the statistics (AsperityParameters),
    the seating options of the parametric laws, their height `distribution`, the Tang & Jiao
    `variant`, Tang's `substrate` options, the measured summit list (topography.empirical_summits
    of the analysis; None: not measured) and the geometric overlap curve (closure, ratio) or None.
    For the laws built from the walls themselves: their `aperture`, `composite_modulus` and the
    `stresses` of the contact curve. `law(key)` builds each derived law once (a composed law
    reuses its base)."""

    parameters: AsperityParameters
    seat: dict
    distribution: str = "gaussian"
    variant: str = "I1"
    substrate: dict = dataclasses.field(default_factory=dict)
    summits: Optional[list] = None
    overlap: Optional[tuple] = None
    aperture: object = None                 # the walls' aperture (topography.Surface), for "walls"
    composite_modulus: Optional[float] = None   # E* [Pa], for "walls"
    stresses: Optional[Sequence[float]] = None  # the loads of the exact contact curve [Pa]
    _built: dict = dataclasses.field(default_factory=dict, repr=False)

    def law(self, key: str) -> ClosureLaw:
        """The closure law registered under key, built from these inputs once and then reused."""
        if key not in self._built:
            self._built[key] = topography_laws()[key].topography(self)
        return self._built[key]


def _parametric(build_law, substrate: bool) -> Callable[[TopographyInputs], ClosureLaw]:
    """GW or Tang (`substrate`: with Tang's options) on the parametric height distribution,
    seated as asked."""
    def build(x: TopographyInputs) -> ClosureLaw:
        return build_law(x.parameters, distribution=x.distribution, **x.seat,
                         **(x.substrate if substrate else {}))
    return build


def _on_summits(build_law, substrate: bool) -> Callable[[TopographyInputs], ClosureLaw]:
    """GW or Tang over the measured summit list (each summit its own radius, seated at the highest)."""
    def build(x: TopographyInputs) -> ClosureLaw:
        return build_law(x.parameters, distribution=x.summits, **(x.substrate if substrate else {}))
    return build


def _tang_jiao_over(base: str, variant: Optional[str] = None, geometric: bool = False):
    """Tang & Jiao's cell over the derived law `base` (`variant`: fixed, or the inputs' own)."""
    def build(x: TopographyInputs) -> ClosureLaw:
        options = dict(base=x.law(base), variant=variant or x.variant)
        if geometric:
            options.update(overlap_closure=x.overlap[0], overlap_area_ratio=x.overlap[1])
        return _TANG_JIAO_BUILD(None, **options)
    return build


for _key, _label, _description, _build, _optional, _options, _derived, _row in (
        ("greenwood_williamson", "GW", "Greenwood-Williamson on the composite topography (theory §2)",
         _GW_BUILD, _ASPERITY_KEYS, ("distribution",), _parametric(_GW_BUILD, substrate=False),
         "gw|first contact"),
        ("tang_substrate", "Tang", "GW with Tang's substrate deformation (theory §4)",
         _TANG_BUILD, _ASPERITY_KEYS | _SUBSTRATE_KEYS, None, _parametric(_TANG_BUILD, substrate=True),
         "tang|first contact"),
        ("tang_jiao", "Tang & Jiao", "Tang & Jiao's interaction cell over Tang's substrate law (theory §5)",
         _TANG_JIAO_BUILD, _ASPERITY_KEYS | _SUBSTRATE_KEYS | {"variant"},
         ("distribution", "base", "variant", "base_radius"), _tang_jiao_over("tang_substrate"),
         "tj_I1_Tang|first contact")):
    register(LawRecord(
        _key, _label, _description, _build, _STATISTICS_KEYS, _optional, _asperity_from_file(_build),
        None if _options is None else CalibrationSpec((_ETA, _SIGMA_S), _gw_type(_build is _TANG_JIAO_BUILD),
                                                      _gw_type_guess, needs=_GIVEN, options=_options,
                                                      fit_offset=True),
        asperity=True, topography=_derived, ladder_row=_row))


# ---- a law with history: the hysteretic wrapper of any law above ------------------------------
# its own parameters r and m: HISTORY_PARAMETERS (NormalHysteresis.parameter_specs, at the top)


def _virgin_record(key) -> LawRecord:
    """The record of a virgin law: registered, and without history itself."""
    record = get(key) if isinstance(key, str) else None
    if record is None or record.history:
        raise ValueError(f"virgin = {key!r}: name a law without history, one of "
                         f"{', '.join(sorted(k for k, r in parametric_laws().items() if not r.history))}")
    return record


def _history_build(parameters: Optional[AsperityParameters] = None, *, virgin=None,
                   permanent_fraction=None, unloading_exponent=None, **options) -> ClosureLaw:
    """NormalHysteresis over `virgin`: a ready law, or the key of a registered law built from
    `parameters` and `options` (its own builder's)."""
    if permanent_fraction is None or unloading_exponent is None or virgin is None:
        raise ValueError("normal hysteresis: give virgin (a law or its key), permanent_fraction r "
                         "and unloading_exponent m (docs/hysteresis.md)")
    if isinstance(virgin, ClosureLaw):
        if parameters is not None or options:
            raise ValueError("normal hysteresis: a ready virgin law takes no further parameters, got "
                             f"{', '.join(options) or 'AsperityParameters'}")
    else:
        virgin = _virgin_record(virgin).build(parameters, **options)
    return NormalHysteresis(virgin, permanent_fraction, unloading_exponent)


def _history_from_file(values: dict) -> ClosureLaw:
    """From file keys: r and m, `virgin` (a key) and the virgin law's own keys (laws.read_law_file
    checks them against the virgin's record)."""
    rest = dict(values)
    virgin = _virgin_record(rest.pop("virgin"))
    r, m = (rest.pop(q.file_key) for q in HISTORY_PARAMETERS)
    return NormalHysteresis(virgin.from_file_values(rest), r, m)


register(LawRecord(
    "normal_hysteresis", "hysteretic",
    "any law above as the virgin curve, with unloading/reloading branches and a permanent "
    "closure set by the largest closure reached (docs/hysteresis.md)",
    _history_build, frozenset({"virgin"} | {q.file_key for q in HISTORY_PARAMETERS}), frozenset(),
    _history_from_file, None, HISTORY_PARAMETERS, history=True))


# ---- laws derived from a topography only ---------------------------------------------------------
#: The law recommended for a joint described by its topography, and why. Evidence:
#: bench/results/accuracy_ladder.md (every law against the exact elastic contact, BEM, of
#: the same walls on the project's synthetic granite-like and sandstone-like joints).
RECOMMENDED = "tang_jiao_i2_gw"
RECOMMENDATION = (
    "Tang & Jiao I2 over GW, seated at the measured first contact: of the parametric laws "
    "rockjoint offers it has the smallest mean closure error against exact elastic contact (BEM) "
    "of the same walls on the project's synthetic joints (loads 1-30 MPa; the errors per joint "
    "family and its cost: bench/results/accuracy_ladder.md, and its JSON that rockjoint.scenes.ladder "
    "reads).")


def derived_law(key: str, label: str, description: str, topography, needs: str = "statistics",
                ladder_row: Optional[str] = None) -> LawRecord:
    """The record of a law derived from a topography only (no parameter builder, no file keys)."""
    return LawRecord(key, label, description, None, frozenset(), frozenset(), None,
                     topography=topography, needs=needs, ladder_row=ladder_row)


for _record in (
        derived_law(RECOMMENDED, "Tang & Jiao I2 over GW (recommended)", RECOMMENDATION,
                    _tang_jiao_over("greenwood_williamson", "I2"), ladder_row="tj_I2_GW|first contact"),
        derived_law("greenwood_williamson_empirical", "GW (empirical summits)",
                    REGISTRY["greenwood_williamson"].description, _on_summits(_GW_BUILD, substrate=False),
                    needs="summits", ladder_row="gw_empirical"),
        derived_law("tang_substrate_empirical", "Tang (empirical summits)", REGISTRY["tang_substrate"].description,
                    _on_summits(_TANG_BUILD, substrate=True), needs="summits", ladder_row="tang_empirical"),
        derived_law("tang_jiao_empirical", "Tang & Jiao (empirical summits)", REGISTRY["tang_jiao"].description,
                    _tang_jiao_over("tang_substrate_empirical"), needs="summits",
                    ladder_row="tj_I1_tang_empirical"),
        derived_law("tang_jiao_empirical_geometric", "Tang & Jiao (empirical, geometric area)",
                    "Tang & Jiao over the empirical Tang law with the geometric overlap ratio "
                    "fraction{e <= Δ} in Eq. (2) (theory §3, §5)",
                    _tang_jiao_over("tang_substrate_empirical", geometric=True), needs="overlap")):
    register(_record)
# The walls' exact contact (BEM) registers itself from rockjoint.contact, beside its solver.
