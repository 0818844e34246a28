"""`python3 -m rockjoint tabulate params.toml -o law.rjt [--plot law.png]`: tabulate a closure
law described in a TOML parameter file (user units MPa, mm, GPa, stated in every key) into a
.rjt table file, and optionally plot the table against its source.

Example parameter file::

    [law]
    model = "barton_bandis"
    initial_normal_stiffness_MPa_per_mm = 20.0
    maximum_closure_mm = 0.3

    [table]
    maximum_stress_MPa = 30.0          # or maximum_closure_mm
    tolerance = 1e-6                   # relative error of σ and k
    # residual_stiffness_MPa_per_mm = 0.0   (default: 1e-6 σ_max/Δ_max; 0: strict open law)
    # maximum_knots = 20000

Models and their [law] keys are listed by ``--list-models``.
"""
from __future__ import annotations

import math
import tomllib

MM = 1e-3          # m per mm
MPA = 1e6          # Pa per MPa
GPA = 1e9          # Pa per GPa
MPA_PER_MM = 1e9   # Pa/m per MPa/mm
PER_MM2 = 1e6      # 1/m² per 1/mm²


def _asperity_parameters(values: dict):
    """(E* [Pa], η [1/m²], β [m], σ_s [m]) from the asperity keys."""
    import rockjoint
    if "composite_modulus_GPa" in values:
        e_star = values["composite_modulus_GPa"] * GPA
    else:
        e_star = rockjoint.composite_modulus(values["young_modulus_GPa"] * GPA,
                                             values["poisson_ratio"])
    return (e_star, values["summit_density_per_mm2"] * PER_MM2, values["summit_radius_mm"] * MM,
            values["summit_height_std_mm"] * MM)


def _asperity_law(model: str, values: dict):
    """GW-type laws through their Python bindings (when this build has them)."""
    import rockjoint
    e_star, eta, beta, sigma_s = _asperity_parameters(values)
    common = dict(composite_modulus=e_star, summit_density=eta, summit_radius=beta,
                  summit_height_std=sigma_s)
    distribution = values.get("height_distribution", "gaussian")
    substrate = {}
    if model in ("tang_substrate", "tang_jiao"):
        substrate["deflection_coefficient"] = values.get("deflection_coefficient",
                                                         8.0 / (3.0 * math.pi))
        if "base_radius_mm" in values:
            substrate["base_radius"] = values["base_radius_mm"] * MM
    cls_name = "GreenwoodWilliamson" if model == "greenwood_williamson" else "TangSubstrate"
    cls = getattr(rockjoint, cls_name, None)
    if cls is None:
        raise ValueError(f"model '{model}' needs rockjoint.{cls_name}, which this build does "
                         "not provide")
    try:
        base = cls(**common, distribution=distribution, **substrate)
    except TypeError as err:
        raise ValueError(f"model '{model}': rockjoint.{cls_name} rejected the parameters: "
                         f"{err}") from err
    if model == "tang_jiao":
        return rockjoint.TangJiao(base, variant=values.get("variant", "I1"))
    return base


_ASPERITY_KEYS = {"composite_modulus_GPa", "young_modulus_GPa", "poisson_ratio",
                  "summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm",
                  "height_distribution"}
_SUBSTRATE_KEYS = {"deflection_coefficient", "base_radius_mm"}

#: model -> (required keys, optional keys, factory(values) -> law). Units in the key names.
MODELS = {
    "barton_bandis": (
        {"initial_normal_stiffness_MPa_per_mm", "maximum_closure_mm"}, set(),
        lambda v: __import__("rockjoint").BartonBandis(
            v["initial_normal_stiffness_MPa_per_mm"] * MPA_PER_MM, v["maximum_closure_mm"] * MM)),
    "logarithmic": (
        {"closure_scale_mm", "seating_stress_MPa"}, set(),
        lambda v: __import__("rockjoint").LogarithmicLaw(v["closure_scale_mm"] * MM,
                                                         v["seating_stress_MPa"] * MPA)),
    "exponential": (
        {"maximum_closure_mm", "characteristic_stress_MPa"}, set(),
        lambda v: __import__("rockjoint").ExponentialLaw(v["maximum_closure_mm"] * MM,
                                                         v["characteristic_stress_MPa"] * MPA)),
    "greenwood_williamson": (
        {"summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm"},
        _ASPERITY_KEYS, lambda v: _asperity_law("greenwood_williamson", v)),
    "tang_substrate": (
        {"summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm"},
        _ASPERITY_KEYS | _SUBSTRATE_KEYS, lambda v: _asperity_law("tang_substrate", v)),
    "tang_jiao": (
        {"summit_density_per_mm2", "summit_radius_mm", "summit_height_std_mm"},
        _ASPERITY_KEYS | _SUBSTRATE_KEYS | {"variant"}, lambda v: _asperity_law("tang_jiao", v)),
}

_TABLE_KEYS = {"maximum_stress_MPa", "maximum_closure_mm", "tolerance",
               "residual_stiffness_MPa_per_mm", "maximum_knots"}


def read_parameters(path: str):
    """(law, table options dict) from a TOML parameter file; ValueError naming the key."""
    with open(path, "rb") as f:
        try:
            doc = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise ValueError(f"{path}: not valid TOML: {err}") from err
    for section in doc:
        if section not in ("law", "table"):
            raise ValueError(f"{path}: unknown section [{section}]; expected [law] and [table]")
    law_doc = dict(doc.get("law", {}))
    model = law_doc.pop("model", None)
    if model not in MODELS:
        raise ValueError(f"{path}: [law] model = {model!r}; expected one of "
                         f"{', '.join(sorted(MODELS))}")
    required, optional, factory = MODELS[model]
    missing = sorted(required - law_doc.keys())
    if model in ("greenwood_williamson", "tang_substrate", "tang_jiao") and not (
            "composite_modulus_GPa" in law_doc
            or {"young_modulus_GPa", "poisson_ratio"} <= law_doc.keys()):
        missing.append("composite_modulus_GPa (or young_modulus_GPa and poisson_ratio)")
    if missing:
        raise ValueError(f"{path}: [law] model {model} is missing {', '.join(missing)}")
    unknown = sorted(law_doc.keys() - required - optional)
    if unknown:
        raise ValueError(f"{path}: [law] unknown key(s) {', '.join(unknown)} for model {model}; "
                         f"expected {', '.join(sorted(required | optional))}")
    for key, value in law_doc.items():
        if key not in ("height_distribution", "variant") and (
                isinstance(value, bool) or not isinstance(value, (int, float))):
            raise ValueError(f"{path}: [law] {key} = {value!r} must be a number")
    law = factory(law_doc)

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
    return law, options


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "tabulate", help="tabulate a closure law from a TOML parameter file into a .rjt table",
        description="Tabulate a closure law (parameters in a TOML file, units MPa/mm/GPa as "
                    "named in its keys) with error control into a .rjt table file.")
    p.add_argument("parameters", nargs="?", help="TOML parameter file ([law] and [table])")
    p.add_argument("-o", "--output", help="table file to write (.rjt)")
    p.add_argument("--plot", help="PNG of the table against its source")
    p.add_argument("--tolerance", type=float, help="override [table] tolerance")
    p.add_argument("--list-models", action="store_true", help="list models and their keys")
    p.set_defaults(func=run)


def run(args) -> int:
    if args.list_models:
        for name, (required, optional, _) in MODELS.items():
            print(f"{name}: requires {', '.join(sorted(required))}"
                  + (f"; optional {', '.join(sorted(optional - required))}" if optional else ""))
        return 0
    if not args.parameters or not args.output:
        raise ValueError("give a parameter file and -o/--output (or --list-models)")
    from ..tabulation import plot_table, tabulate

    law, options = read_parameters(args.parameters)
    if args.tolerance is not None:
        options["tolerance"] = args.tolerance
    try:
        table = tabulate(law, **options)
    except RuntimeError as err:  # knot budget exceeded: a user-facing error here
        raise ValueError(str(err)) from err
    table.save(args.output)
    print(f"{table.source_model}: {table.knot_count} knots, tolerance {table.tolerance:g} "
          f"(checked σ {table.checked_error_stress:.2g}, k {table.checked_error_stiffness:.2g}), "
          f"closure 0..{table.table_maximum_closure * 1e3:.6g} mm, "
          f"stress 0..{table.table_maximum_stress * 1e-6:.6g} MPa -> {args.output}")
    if args.plot:
        plot_table(table, law, args.plot)
        print(f"plot -> {args.plot}")
    return 0
