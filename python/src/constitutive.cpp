// SPDX-License-Identifier: MIT
// Bindings of rockjoint::constitutive (one file per C++ namespace, DOLFINx style): the closure
// laws and their inverse, the asperity models (GW, Tang's substrate), Tang & Jiao's interaction
// cell and law, and the tabulated law; declare_constitutive binds them all.
#include "array_helpers.hpp"

#include <rockjoint/constitutive/asperity_parameters.hpp>
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/closure_law.hpp>
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/hertz.hpp>
#include <rockjoint/constitutive/interaction_cell.hpp>
#include <rockjoint/constitutive/interaction_cell_numeric.hpp>
#include <rockjoint/constitutive/normal_hysteresis.hpp>
#include <rockjoint/constitutive/parameter_spec.hpp>
#include <rockjoint/constitutive/substrate.hpp>
#include <rockjoint/constitutive/summit_population_law.hpp>
#include <rockjoint/constitutive/tabulated_law.hpp>
#include <rockjoint/constitutive/tang_jiao.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace py = pybind11;
using namespace rockjoint::constitutive;

namespace rockjoint::python
{
// ---- constitutive ------------------------------------------------------------------------------
namespace
{
/// Δ(σ) over an array (scalar in → scalar out).
py::object inverse_array(const ClosureLaw& law, const DoubleArray& stress)
{
  require_no_nan(stress, "normal_stress");
  DoubleArray out = empty_like(stress);
  const double* in = stress.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < stress.size(); ++i)
    o[i] = law.closure_at_stress(in[i]);
  if (stress.ndim() == 0)
    return out.attr("item")();
  return out;
}

} // namespace

void declare_laws(py::module_& m)
{
  // The per-point status codes of a joint's state (`coupling.state(u)["status"]`) are these
  // values; docs/user-model.md ("Joint point status") explains each, as closure_law.hpp does.
  py::enum_<Status>(m, "Status", "Outcome of one law evaluation (the per-point status code of a joint)")
      .value("contact", Status::contact, "0: closure Δ > 0 inside the law's domain")
      .value("open", Status::open, "1: Δ <= 0, the joint is open (zero response, or the residual stiffness)")
      .value("validity_limit", Status::validity_limit,
             "2: past the law's range: a table beyond its last knot (its linear continuation), "
             "a Tang & Jiao law at its cap (response frozen)")
      .value("beyond_maximum_closure", Status::beyond_maximum_closure,
             "3: Δ at or past the law's maximum closure: σ = k = +inf")
      .value("invalid_closure", Status::invalid_closure, "4: Δ is NaN: the response is NaN")
      .value("quadrature_not_converged", Status::quadrature_not_converged,
             "5: an integral of the law missed its tolerance: best estimate returned");

  py::class_<Parameter>(m, "Parameter",
                        "One named parameter of a closure law, as the law reports it "
                        "(ClosureLaw.parameters): name, value in SI, unit")
      .def_readonly("name", &Parameter::name, "The parameter's name, e.g. 'maximum_closure'")
      .def_readonly("value", &Parameter::value, "Its value, in the SI unit `unit`")
      .def_readonly("unit", &Parameter::unit, "Its SI unit, e.g. 'm', 'Pa', 'Pa/m', '-'")
      .def("__repr__", [](const Parameter& p)
           { return p.name + "=" + std::to_string(p.value) + " " + p.unit; });

  py::class_<ParameterSpec>(
      m, "ParameterSpec",
      "What a law's parameter is, from the law's own C++ code: keyword, symbol, SI unit, the "
      "unit of parameter files and reports, and the admissible range its constructor checks")
      .def_readonly("name", &ParameterSpec::name, "keyword of the SI constructor argument")
      .def_readonly("symbol", &ParameterSpec::symbol, "symbol in the theory")
      .def_readonly("unit", &ParameterSpec::unit, "SI unit ('-': dimensionless)")
      .def_readonly("file_unit", &ParameterSpec::file_unit, "unit of parameter files and reports")
      .def_readonly("lower", &ParameterSpec::lower, "lower bound of the range")
      .def_readonly("lower_inclusive", &ParameterSpec::lower_inclusive, "whether lower itself is admissible")
      .def_readonly("upper", &ParameterSpec::upper, "upper bound of the range (inf: none)")
      .def_readonly("upper_inclusive", &ParameterSpec::upper_inclusive, "whether upper itself is admissible")
      .def_property_readonly("range", &ParameterSpec::range,
                             "the range in words, e.g. 'finite and > 0', 'in [0, 1)'")
      .def("admits", &ParameterSpec::admits, py::arg("value"),
           "whether value [SI] lies in the admissible range")
      .def("__repr__", [](const ParameterSpec& s)
           { return "ParameterSpec(" + s.name + " " + s.symbol + " [" + s.unit + "], " + s.range() + ")"; });

  py::class_<ClosureLaw, std::shared_ptr<ClosureLaw>>(
      m, "ClosureLaw", "Normal-closure law σ(Δ) of a rough joint (SI: Pa, m)")
      .def_property_readonly("name", &ClosureLaw::name,
                             "The law's model name, e.g. 'barton_bandis' (written into tables)")
      .def_property_readonly("parameters", &ClosureLaw::parameters,
                             "The law's parameters: a list of Parameter (name, SI value, unit)")
      .def_property_readonly("provides_contact_area", &ClosureLaw::provides_contact_area,
                             "True if the law models the contact-area ratio A/A0 (asperity "
                             "laws); False if contact_area_ratio is 0 (empirical laws, tables)")
      .def_property_readonly("maximum_closure", &ClosureLaw::maximum_closure,
                             "Supremum of admissible closures [m] (inf if none)")
      .def_property_readonly("seating_stress", &ClosureLaw::seating_stress,
                             "Stress of the model at Δ = 0 [Pa], subtracted so σ(0) = 0")
      .def("evaluate", &evaluate_to_numpy<ClosureLaw>, py::arg("closure"),
           "(σ [Pa], k [Pa/m], A/A0 [-], status) at closure Δ [m]; arrays shaped like Δ")
      .def("normal_stress", &evaluate_column<0, ClosureLaw>, py::arg("closure"), "σ(Δ) [Pa]")
      .def("normal_stiffness", &evaluate_column<1, ClosureLaw>, py::arg("closure"), "k(Δ) = dσ/dΔ [Pa/m]")
      .def("contact_area_ratio", &evaluate_column<2, ClosureLaw>, py::arg("closure"), "A/A0(Δ) [-]")
      .def("closure_at_stress", &inverse_array, py::arg("normal_stress"),
           "Inverse Δ(σ) [m] for σ >= 0 [Pa]")
      .def_property_readonly("has_history", &ClosureLaw::has_history,
                             "True if the response depends on the largest closure reached")
      .def(
          "evaluate_with_history",
          [](const ClosureLaw& law, double closure, double maximum_closure)
          {
            const HistoryResponse r = law.evaluate_with_history(closure, maximum_closure);
            py::dict d;
            d["normal_stress"] = r.response.normal_stress;
            d["normal_stiffness"] = r.response.normal_stiffness;
            d["on_virgin_curve"] = r.on_virgin_curve;
            d["maximum_closure"] = r.maximum_closure;
            d["permanent_closure"] = r.permanent_closure;
            d["status"] = std::string(to_string(r.response.status));
            return d;
          },
          py::arg("closure"), py::arg("maximum_closure"),
          "σ [Pa], k = ∂σ/∂Δ [Pa/m] at closure Δ [m] given the largest closure reached before "
          "[m] (a law without history: its own curve)");

  py::class_<BartonBandis, ClosureLaw, std::shared_ptr<BartonBandis>>(
      m, "BartonBandis", "Barton-Bandis hyperbola σ = K_ni Δ / (1 - Δ/V_m)")
      .def(py::init<double, double>(), py::arg("initial_normal_stiffness"),
           py::arg("maximum_closure"))
      .def_static("parameter_specs", &BartonBandis::parameter_specs, "The constructor's parameters: name, symbol, SI unit, file unit and admissible range (ParameterSpec)")
      .def_static(
          "from_joint_properties",
          [](double jrc, double jcs, double aj)
          { return std::make_shared<BartonBandis>(BartonBandis::from_joint_properties(jrc, jcs, aj)); },
          py::arg("jrc"), py::arg("jcs"), py::arg("initial_aperture"),
          "Bandis et al. (1983) estimates from JRC [-], JCS [Pa], initial aperture [m]")
      .def_property_readonly("initial_normal_stiffness", &BartonBandis::initial_normal_stiffness,
                             "K_ni = dσ/dΔ at Δ = 0 [Pa/m]");

  py::class_<LogarithmicLaw, ClosureLaw, std::shared_ptr<LogarithmicLaw>>(
      m, "LogarithmicLaw", "Δ = B ln(σ_t/σ0); returns σ = σ_t - σ0")
      .def(py::init<double, double>(), py::arg("closure_scale"), py::arg("seating_stress"))
      .def_static("parameter_specs", &LogarithmicLaw::parameter_specs, "The constructor's parameters: name, symbol, SI unit, file unit and admissible range (ParameterSpec)");

  py::class_<ExponentialLaw, ClosureLaw, std::shared_ptr<ExponentialLaw>>(
      m, "ExponentialLaw", "Δ = V_m (1 - exp(-σ/σ_c))")
      .def(py::init<double, double>(), py::arg("maximum_closure"),
           py::arg("characteristic_stress"))
      .def_static("parameter_specs", &ExponentialLaw::parameter_specs, "The constructor's parameters: name, symbol, SI unit, file unit and admissible range (ParameterSpec)");

  py::class_<NormalHysteresis, ClosureLaw, std::shared_ptr<NormalHysteresis>>(
      m, "NormalHysteresis",
      "Virgin closure law with Bandis-type unloading/reloading branches set by the largest "
      "closure reached (docs/hysteresis.md, H1-H4): a law with history; without history "
      "(evaluate, closure_at_stress) it is the virgin curve")
      .def(py::init<std::shared_ptr<const ClosureLaw>, double, double>(), py::arg("virgin"),
           py::arg("permanent_fraction"), py::arg("unloading_exponent"))
      .def_static("parameter_specs", &NormalHysteresis::parameter_specs,
                  "The history's own parameters r and m (beside the virgin law's): ParameterSpec")
      .def_property_readonly("virgin", [](const NormalHysteresis& h)
                             { return std::const_pointer_cast<ClosureLaw>(h.virgin_law()); },
                             "The virgin (first-loading) closure law")
      .def_property_readonly("permanent_fraction", &NormalHysteresis::permanent_fraction,
                             "r [-], in [0, 1): the permanent closure Δ_p = r Δ_m left after "
                             "unloading from the largest closure Δ_m (docs/hysteresis.md, H2)")
      .def_property_readonly("unloading_exponent", &NormalHysteresis::unloading_exponent,
                             "n [-], > 0: shape exponent of the unloading/reloading branch "
                             "(docs/hysteresis.md, H3)")
      .def("permanent_closure", &NormalHysteresis::permanent_closure, py::arg("maximum_closure"),
           "Δ_p = r Δ_m [m]")
      .def(
          "closure_path",
          [](const NormalHysteresis& h, const DoubleArray& stress, double maximum_closure)
          {
            require_no_nan(stress, "stress");
            const std::vector<double> c = h.closure_path(as_span(stress), maximum_closure);
            DoubleArray out = empty_like(stress);
            std::copy(c.begin(), c.end(), out.mutable_data());
            return out;
          },
          py::arg("stress"), py::arg("maximum_closure") = 0.0,
          "closures [m] along a path of normal stresses [Pa] (load cycles), from Δ_m");

  m.def("composite_modulus", py::overload_cast<double, double>(&composite_modulus),
        py::arg("young"), py::arg("poisson"), "E* = E / (2(1-ν²)) [Pa] of two walls of one rock");
  m.def("composite_modulus",
        py::overload_cast<double, double, double, double>(&composite_modulus), py::arg("young1"),
        py::arg("poisson1"), py::arg("young2"), py::arg("poisson2"),
        "1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 [Pa]");
}

// ---- asperity models ---------------------------------------------------------------------------
namespace
{
/// The distribution argument: "gaussian", "exponential", or (heights, radii, area).
struct DistributionChoice
{
  HeightDistribution kind = HeightDistribution::gaussian;
  std::optional<EmpiricalSummits> summits;
};

DistributionChoice parse_distribution(const std::string& owner, const py::object& d)
{
  if (py::isinstance<py::str>(d))
  {
    const auto s = d.cast<std::string>();
    if (s == "gaussian")
      return {HeightDistribution::gaussian, std::nullopt};
    if (s == "exponential")
      return {HeightDistribution::exponential, std::nullopt};
    throw py::value_error(owner + ": distribution '" + s
                          + "' is invalid; it must be 'gaussian', 'exponential' or a "
                            "(heights [m], radii [m], area [m^2]) triple");
  }
  py::tuple t;
  try
  {
    t = py::tuple(d);
  }
  catch (const py::error_already_set&)
  {
    throw py::value_error(owner
                          + ": distribution must be 'gaussian', 'exponential' or a "
                            "(heights [m], radii [m], area [m^2]) triple");
  }
  if (t.size() != 3)
    throw py::value_error(owner
                          + ": an empirical distribution is a (heights [m], radii [m], "
                            "area [m^2]) triple; got "
                          + std::to_string(t.size()) + " items");
  auto heights = t[0].cast<DoubleArray>();
  auto radii = t[1].cast<DoubleArray>();
  const auto h = as_span(heights), r = as_span(radii);
  return {HeightDistribution::empirical,
          EmpiricalSummits({h.begin(), h.end()}, {r.begin(), r.end()}, t[2].cast<double>())};
}

SeatingReference parse_reference(const std::string& owner,
                                 std::optional<double> reference_separation,
                                 std::optional<double> seating_stress)
{
  if (reference_separation && seating_stress)
    throw py::value_error(owner + ": give reference_separation or seating_stress, not both");
  if (reference_separation)
    return SeatingReference::at_separation(*reference_separation);
  if (seating_stress)
    return SeatingReference::at_stress(*seating_stress);
  return SeatingReference::automatic();
}

/// Statistics for a parametric distribution (all required), none for an empirical list.
AsperityParameters parse_statistics(const std::string& owner, const DistributionChoice& dist,
                                    double modulus, std::optional<double> density,
                                    std::optional<double> radius, std::optional<double> height_std)
{
  if (dist.summits)
  {
    if (density || radius || height_std)
      throw py::value_error(owner
                            + ": summit_density, summit_radius and summit_height_std are "
                              "derived from an empirical (heights, radii, area) list; "
                              "do not give them");
    return {};
  }
  for (auto [name, value] :
       {std::pair{"summit_density", density}, std::pair{"summit_radius", radius},
        std::pair{"summit_height_std", height_std}})
    if (!value)
      throw py::value_error(owner + ": parameter '" + name + "' is required for distribution '"
                            + to_string(dist.kind) + "'");
  return {modulus, *density, *radius, *height_std};
}

std::shared_ptr<GreenwoodWilliamson> make_gw(double modulus, std::optional<double> density,
                                             std::optional<double> radius,
                                             std::optional<double> height_std,
                                             const py::object& distribution,
                                             std::optional<double> reference_separation,
                                             std::optional<double> seating_stress, double tolerance)
{
  const std::string owner = "GreenwoodWilliamson";
  DistributionChoice dist = parse_distribution(owner, distribution);
  const AsperityParameters p = parse_statistics(owner, dist, modulus, density, radius, height_std);
  const SeatingReference ref = parse_reference(owner, reference_separation, seating_stress);
  if (dist.summits)
    return std::make_shared<GreenwoodWilliamson>(modulus, std::move(*dist.summits), ref);
  return std::make_shared<GreenwoodWilliamson>(p, dist.kind, ref, tolerance);
}

std::shared_ptr<TangSubstrate>
make_tang(double modulus, std::optional<double> density, std::optional<double> radius,
          std::optional<double> height_std, const py::object& distribution,
          double deflection_coefficient, std::optional<double> base_radius,
          std::optional<double> reference_separation, std::optional<double> seating_stress,
          double tolerance)
{
  const std::string owner = "TangSubstrate";
  DistributionChoice dist = parse_distribution(owner, distribution);
  const AsperityParameters p = parse_statistics(owner, dist, modulus, density, radius, height_std);
  const SeatingReference ref = parse_reference(owner, reference_separation, seating_stress);
  const SubstrateParameters sub{deflection_coefficient, base_radius};
  if (dist.summits)
    return std::make_shared<TangSubstrate>(modulus, std::move(*dist.summits), sub, ref);
  return std::make_shared<TangSubstrate>(p, dist.kind, sub, ref, tolerance);
}

py::tuple separation_response(const SummitPopulationLaw& law, const DoubleArray& separation)
{
  require_no_nan(separation, "separation");
  DoubleArray s = empty_like(separation), k = empty_like(separation), a = empty_like(separation),
              rate = empty_like(separation);
  const double* d = separation.data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < separation.size(); ++i)
    {
      const ClosureResponse r = law.response_at_separation(d[i]);
      s.mutable_data()[i] = r.normal_stress;
      k.mutable_data()[i] = r.normal_stiffness;
      a.mutable_data()[i] = r.contact_area_ratio;
      rate.mutable_data()[i] = r.contact_area_rate;
    }
  }
  if (separation.ndim() == 0)
    return py::make_tuple(s.attr("item")(), k.attr("item")(), a.attr("item")(),
                          rate.attr("item")());
  return py::make_tuple(s, k, a, rate);
}

const char* common_doc
    = "composite_modulus: E* [Pa] with 1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 (NOT E/(1-ν²)).\n"
      "summit_density η [1/m²], summit_radius β [m], summit_height_std σ_s [m]: required for "
      "distribution 'gaussian' (mean 0) or 'exponential' (f = e^{-z/σ_s}/σ_s, z >= 0); "
      "omitted for an empirical distribution given as (heights [m], radii [m], area [m²]) "
      "(η = N/A0, β = mean radius, σ_s = std of heights; each summit keeps its radius).\n"
      "Seating convention: d = d0 - Δ and σ(Δ) = σ_model(d0 - Δ) - σ_model(d0). Reference d0: "
      "reference_separation [m], or seating_stress [Pa] (solve σ_model(d0) = σ_seat), or by "
      "default the mean summit height + 3.5 σ_s (highest summit of an empirical list).\n"
      "quadrature_tolerance: relative tolerance of the height quadrature (unused for an "
      "empirical list).";
} // namespace

void declare_asperity_models(py::module_& m)
{
  // AsperityParameters/AsperityLaw may have been registered by another binding file.
  if (!py::detail::get_type_info(typeid(AsperityParameters)))
    py::class_<AsperityParameters>(
        m, "AsperityParameters",
        "Roughness statistics of the composite topography (SI): the one parameter type of the "
        "asperity laws, the topography analysis and the parameter files")
        .def(py::init(
                 [](double e, double eta, double beta, double sigma, std::optional<double> h)
                 {
                   AsperityParameters p{e, eta, beta, sigma};
                   if (h)
                     p.sampling_interval = *h;
                   validate(p, "AsperityParameters");
                   return p;
                 }),
             py::arg("composite_modulus"), py::arg("summit_density"),
             py::arg("summit_radius"), py::arg("summit_height_std"),
             py::arg("sampling_interval") = py::none())
        .def_static("parameter_specs", &AsperityParameters::parameter_specs,
                    "E*, η, β, σ_s and h: name, symbol, SI unit, file unit and range (ParameterSpec)")
        .def_readonly("composite_modulus", &AsperityParameters::composite_modulus, "E* [Pa]")
        .def_readonly("summit_density", &AsperityParameters::summit_density, "η [1/m²]")
        .def_readonly("summit_radius", &AsperityParameters::summit_radius, "β [m]")
        .def_readonly("summit_height_std", &AsperityParameters::summit_height_std, "σ_s [m]")
        .def_property_readonly(
            "sampling_interval",
            [](const AsperityParameters& p) -> std::optional<double>
            {
              if (std::isnan(p.sampling_interval))
                return std::nullopt;
              return p.sampling_interval;
            },
            "h [m] the statistics belong to, or None if not known")
        .def("__eq__",
             [](const AsperityParameters& a, const AsperityParameters& b)
             {
               auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
               return a.composite_modulus == b.composite_modulus
                      && a.summit_density == b.summit_density && a.summit_radius == b.summit_radius
                      && a.summit_height_std == b.summit_height_std
                      && same(a.sampling_interval, b.sampling_interval);
             })
        .def("__repr__",
             [](const AsperityParameters& p)
             {
               return py::str("AsperityParameters(composite_modulus={!r}, summit_density={!r}, "
                              "summit_radius={!r}, summit_height_std={!r}, "
                              "sampling_interval={!r})")
                   .format(p.composite_modulus, p.summit_density, p.summit_radius,
                           p.summit_height_std,
                           std::isnan(p.sampling_interval) ? py::object(py::none())
                                                           : py::object(py::float_(p.sampling_interval)));
             });
  if (!py::detail::get_type_info(typeid(AsperityLaw)))
    py::class_<AsperityLaw, ClosureLaw, std::shared_ptr<AsperityLaw>>(
        m, "AsperityLaw", "A closure law built on a population of Hertzian summits")
        .def_property_readonly("asperity_parameters", &AsperityLaw::asperity_parameters,
                               "Summit statistics (E* [Pa], η [1/m²], β [m], σ_s [m])");

  py::class_<SummitPopulationLaw, AsperityLaw, std::shared_ptr<SummitPopulationLaw>>(
      m, "SummitPopulationLaw", "Common base of GreenwoodWilliamson and TangSubstrate")
      .def_property_readonly("reference_separation", &SummitPopulationLaw::reference_separation,
                             "Reference (seating) separation d0 [m]")
      .def_property_readonly("distribution", [](const SummitPopulationLaw& l)
                             { return std::string(to_string(l.distribution())); },
                             "The summit-height distribution: 'gaussian', 'exponential' or "
                             "'empirical' (a list of summits)")
      .def_property_readonly("quadrature_tolerance", &SummitPopulationLaw::quadrature_tolerance,
                             "Relative tolerance [-] of the height integrals")
      .def("quadrature_converged", &SummitPopulationLaw::quadrature_converged, py::arg("closure"),
           "Diagnostic: True if every height integral at closure Δ [m] met the tolerance")
      .def("response_at_separation", &separation_response, py::arg("separation"),
           "Un-seated model response at separation d [m]: (σ_model [Pa], k [Pa/m], A/A0 [-], "
           "d(A/A0)/dΔ [1/m])");

  py::class_<GreenwoodWilliamson, SummitPopulationLaw, std::shared_ptr<GreenwoodWilliamson>>(
      m, "GreenwoodWilliamson",
      (std::string("Greenwood-Williamson law: σ = (4/3) E* η β^½ ∫_d^∞ (z-d)^{3/2} f dz per unit "
                   "area, k = dσ/dΔ, A/A0 = π η β ∫ (z-d) f dz (theory §2).\n")
       + common_doc)
          .c_str())
      .def(py::init(&make_gw), py::arg("composite_modulus"), py::arg("summit_density") = py::none(),
           py::arg("summit_radius") = py::none(), py::arg("summit_height_std") = py::none(),
           py::kw_only(), py::arg("distribution") = "gaussian",
           py::arg("reference_separation") = py::none(), py::arg("seating_stress") = py::none(),
           py::arg("quadrature_tolerance") = default_quadrature_tolerance);

  py::class_<TangSubstrate, SummitPopulationLaw, std::shared_ptr<TangSubstrate>>(
      m, "TangSubstrate",
      (std::string("GW with substrate deformation (Tang et al. 2014, f3 of Tang & Jiao 2018, "
                   "theory §4): each summit carries (4/3) E* β^½ g^{3/2} with "
                   "w = g + κ_s √β g^{3/2} / r0.\n")
       + common_doc
       + "\ndeflection_coefficient κ_s [-] (default 8/(3π), centre deflection; "
         "MEAN_DEFLECTION 64/(9π²); RIGID_BASE 2/3; 0 gives GW); base_radius r0 [m] (default "
         "1/(2√η), half the summit spacing).")
          .c_str())
      .def(py::init(&make_tang), py::arg("composite_modulus"),
           py::arg("summit_density") = py::none(), py::arg("summit_radius") = py::none(),
           py::arg("summit_height_std") = py::none(), py::kw_only(),
           py::arg("distribution") = "gaussian",
           py::arg("deflection_coefficient") = substrate::centre_deflection,
           py::arg("base_radius") = py::none(), py::arg("reference_separation") = py::none(),
           py::arg("seating_stress") = py::none(),
           py::arg("quadrature_tolerance") = default_quadrature_tolerance)
      .def_property_readonly("deflection_coefficient", &TangSubstrate::deflection_coefficient,
                             "κ_s [-]")
      .def_property_readonly("base_radius", &TangSubstrate::base_radius, "r0 [m]")
      .def_readonly_static("CENTRE_DEFLECTION", &substrate::centre_deflection,
                           "κ_s = 8/(3π) [-]: the deflection at the centre of the loaded base "
                           "(the default)")
      .def_readonly_static("MEAN_DEFLECTION", &substrate::mean_deflection,
                           "κ_s = 64/(9π²) [-]: the mean deflection over the loaded base")
      .def_readonly_static("RIGID_BASE", &substrate::rigid_base,
                           "κ_s = 2/3 [-]: a rigid circular base");
}

// ---- tang jiao ---------------------------------------------------------------------------------
namespace
{
TangJiaoVariant parse_variant(const std::string& v)
{
  // "as_published" is accepted as the former name of I1 (the project's reading of Eq. (7)).
  if (v == "I1" || v == "i1" || v == "stress_interaction" || v == "as_published")
    return TangJiaoVariant::stress_interaction;
  if (v == "I2" || v == "i2" || v == "kinematic")
    return TangJiaoVariant::kinematic;
  throw py::value_error("TangJiao: variant '" + v
                        + "' is invalid; it must be 'I1' (stress interaction, the project's reading of Eq. (7)) or 'I2' (kinematic)");
}

std::vector<double> to_vector(const std::optional<DoubleArray>& a)
{
  if (!a)
    return {};
  auto s = as_span(*a);
  return {s.begin(), s.end()};
}

std::shared_ptr<TangJiao> make_tang_jiao(std::shared_ptr<ClosureLaw> base,
                                         std::optional<double> modulus,
                                         std::optional<double> radius,
                                         std::optional<double> height_std,
                                         const std::string& variant,
                                         std::optional<DoubleArray> overlap_closure,
                                         std::optional<DoubleArray> overlap_area_ratio,
                                         double maximum_area_root, double maximum_shift_rate)
{
  TangJiaoOptions o;
  o.variant = parse_variant(variant);
  o.overlap_closure = to_vector(overlap_closure);
  o.overlap_area_ratio = to_vector(overlap_area_ratio);
  o.maximum_area_root = maximum_area_root;
  o.maximum_shift_rate = maximum_shift_rate;
  const bool any = modulus || radius || height_std;
  const bool all = modulus && radius && height_std;
  if (!any)
  {
    auto asperity = std::dynamic_pointer_cast<const AsperityLaw>(base);
    if (!base)
      throw py::value_error("TangJiao: parameter 'base' is None; it must be a closure law");
    if (!asperity)
      throw py::value_error("TangJiao: base law '" + base->name()
                            + "' is not an asperity law: give composite_modulus, radius and "
                              "summit_height_std");
    return std::make_shared<TangJiao>(asperity, std::move(o));
  }
  if (!all)
    throw py::value_error("TangJiao: give all of composite_modulus, radius and "
                          "summit_height_std, or none (to take them from an asperity law)");
  return std::make_shared<TangJiao>(std::shared_ptr<const ClosureLaw>(base), *modulus, *radius,
                                    *height_std, std::move(o));
}

py::dict state_dict(const TangJiao::State& s)
{
  py::dict d;
  d["base_stress"] = s.base_stress;
  d["base_stiffness"] = s.base_stiffness;
  d["area_ratio"] = s.area_ratio;
  d["area_rate"] = s.area_rate;
  d["area_root"] = s.area_root;
  d["load_fraction"] = s.load_fraction;
  d["normal_stress"] = s.normal_stress;
  d["normal_stiffness"] = s.normal_stiffness;
  d["closure_shift"] = s.closure_shift;
  d["closure_shift_rate"] = s.closure_shift_rate;
  d["status"] = s.status;
  return d;
}
} // namespace

void declare_tang_jiao(py::module_& m)
{
  py::enum_<TangJiaoLimit>(m, "TangJiaoLimit", "What sets TangJiao.maximum_closure")
      .value("none", TangJiaoLimit::none)
      .value("area_root", TangJiaoLimit::area_root)
      .value("closure_shift_rate", TangJiaoLimit::closure_shift_rate)
      .value("base_law", TangJiaoLimit::base_law);

  py::class_<TangJiao, ClosureLaw, std::shared_ptr<TangJiao>>(
      m, "TangJiao",
      "Tang & Jiao (2018) self-consistent interaction over a base law f3 (theory §5).\n"
      "Two project readings of Eq. (7) (not the paper's words; docs/theory.md §5):\n"
      "I1 (default): F = σ_model/Q(s) - σ_seat/Q(s0), s = √(A/A0), closure unchanged;\n"
      "I2: F at Δ = ξ - ε(ξ), ε = (2F/E*)√(b²-a²).\n"
      "Validity limit at s = maximum_area_root (I2 also at dε/dξ = maximum_shift_rate).")
      .def(py::init(&make_tang_jiao), py::arg("base"), py::arg("composite_modulus") = py::none(),
           py::arg("radius") = py::none(), py::arg("summit_height_std") = py::none(),
           py::arg("variant") = "I1", py::arg("overlap_closure") = py::none(),
           py::arg("overlap_area_ratio") = py::none(), py::arg("maximum_area_root") = 0.99,
           py::arg("maximum_shift_rate") = 0.9,
           "base: any ClosureLaw; composite_modulus E* [Pa], radius R [m] (= β), "
           "summit_height_std σ_s [m]: all three, or none to take them from an asperity law "
           "(GreenwoodWilliamson, TangSubstrate). overlap_closure [m] / overlap_area_ratio [-]: "
           "optional geometric fraction{e <= Δ} samples for Eq. (2) (Δ_0 = 0, monotone).")
      .def_property_readonly("variant", [](const TangJiao& l)
                             { return l.variant() == TangJiaoVariant::kinematic ? "I2" : "I1"; },
                             "The reading of Eq. (7): 'I1' (stress interaction) or 'I2' "
                             "(kinematic closure shift)")
      .def_property_readonly("limit", &TangJiao::limit,
                             "What sets maximum_closure (a TangJiaoLimit)")
      .def_property_readonly("limit_description", &TangJiao::limit_description,
                             "The limit in words, for messages and reports")
      .def_property_readonly("maximum_internal_closure", &TangJiao::maximum_internal_closure,
                             "Internal closure ξ at the validity limit [m]")
      .def_property_readonly("contact_radius", &TangJiao::contact_radius,
                             "Eq. (1): a = (3/4)√(π R σ_s) [m]")
      .def(
          "internal_closure",
          [](const TangJiao& l, const DoubleArray& closure)
          {
            require_no_nan(closure, "closure");
            return py::vectorize([&l](double d) { return l.internal_closure(d); })(closure);
          },
          py::arg("closure"), "I2: internal closure ξ [m] at observed closure Δ [m]")
      .def(
          "state", [](const TangJiao& l, double xi) { return state_dict(l.state(xi)); },
          py::arg("internal_closure"), "Cell state at internal closure ξ [m] (dict)");

  // Closed form of the cell and the paper's algorithm.
  m.def("load_fraction", py::vectorize(&interaction_cell::load_fraction), py::arg("area_root"),
        "Q(s) = (2/π)[arccos s + s√(1-s²)]");
  m.def("interaction_fraction", py::vectorize(&interaction_cell::interaction_fraction),
        py::arg("area_root"), "1 - Q(s), accurate for small s (≈ 4s³/(3π))");

  py::class_<interaction_cell::Cell>(m, "InteractionCell",
                                     "Closed-form self-consistent cell (theory §5), SI units")
      .def(py::init<double, double, double, double>(), py::arg("composite_modulus"),
           py::arg("radius"), py::arg("contact_radius"), py::arg("area_root"))
      .def_property_readonly("territory_radius", &interaction_cell::Cell::territory_radius,
                             "b = a/s [m], the radius of the cell (Eq. (2))")
      .def_property_readonly("mean_pressure", &interaction_cell::Cell::mean_pressure,
                             "Self-consistent mean pressure p̄ = p_m s²/Q(s) [Pa] (Eq. (3))")
      .def_property_readonly("local_approach", &interaction_cell::Cell::local_approach,
                             "Finite-fringe local approach δ_loc = a²/R - (2p̄/E*) √(b²-a²) [m]")
      .def_property_readonly("hertz_load", &interaction_cell::Cell::hertz_load,
                             "Hertz part of the load P_H = (4/3) E* a³/R [N]")
      .def_property_readonly("interaction_load", &interaction_cell::Cell::interaction_load,
                             "Interaction part P_int = 2p̄ [b² arcsin(a/b) - a √(b²-a²)] [N]")
      .def_property_readonly("load", &interaction_cell::Cell::load,
                             "P = P_H + P_int [N], equal to p̄ π b² (self-consistency)")
      .def_property_readonly("closure_shift", &interaction_cell::Cell::closure_shift,
                             "Variant I2 closure shift ε = (2p̄/E*) √(b²-a²) [m]")
      .def(
          "pressure",
          [](const interaction_cell::Cell& c, const DoubleArray& r)
          { return py::vectorize([&c](double x) { return c.pressure(x); })(r); },
          py::arg("r"), "p(r) [Pa] at radius r [m]");

  py::class_<interaction_cell::NumericCell>(
      m, "NumericInteractionCell",
      "The paper's algorithm (Fig. 2): finite-fringe root find on p̄, self-consistency on δ_loc")
      .def(py::init<double, double, double, double, int>(), py::arg("composite_modulus"),
           py::arg("radius"), py::arg("contact_radius"), py::arg("area_root"),
           py::arg("quadrature_order") = 32)
      .def_property_readonly("mean_pressure",
                             [](const interaction_cell::NumericCell& c)
                             { return c.solution().mean_pressure; },
                             "Mean pressure p̄ [Pa] at the solution")
      .def_property_readonly("local_approach",
                             [](const interaction_cell::NumericCell& c)
                             { return c.solution().local_approach; },
                             "Local approach δ_loc [m] at the solution")
      .def_property_readonly("load", [](const interaction_cell::NumericCell& c)
                             { return c.solution().load; }, "Load P [N] of the cell")
      .def_property_readonly("iterations",
                             [](const interaction_cell::NumericCell& c)
                             {
                               return py::make_tuple(c.solution().outer_iterations,
                                                     c.solution().inner_iterations);
                             },
                             "(outer, inner): root-finder iterations on δ_loc "
                             "(self-consistency) and on p̄ (finite fringe, summed)")
      .def_property_readonly("converged", [](const interaction_cell::NumericCell& c)
                             { return c.solution().converged; },
                             "True if both root finds met their tolerances")
      .def(
          "pressure",
          [](const interaction_cell::NumericCell& c, const DoubleArray& r)
          { return py::vectorize([&c](double x) { return c.pressure(x); })(r); },
          py::arg("r"), "p(r) [Pa] at radius r [m]");
}

// ---- tabulation --------------------------------------------------------------------------------
namespace
{
using Table = std::shared_ptr<TabulatedLaw>;

TabulatedLaw::Options options(double tolerance, std::optional<double> residual_stiffness,
                              std::size_t maximum_knots)
{
  TabulatedLaw::Options o;
  o.tolerance = tolerance;
  o.maximum_knots = maximum_knots;
  if (residual_stiffness)
    o.residual_stiffness = *residual_stiffness;
  return o;
}

py::array_t<double> to_numpy(const std::vector<double>& v)
{
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

/// A file error is bad input: ValueError (the CLI prints it as a one-line error).
template <class F>
auto file_errors_as_value_errors(F&& f)
{
  try
  {
    return f();
  }
  catch (const std::runtime_error& e)
  {
    throw py::value_error(e.what());
  }
}
} // namespace

void declare_tabulation(py::module_& m)
{
  py::class_<TabulatedLaw, ClosureLaw, Table>(
      m, "TabulatedLaw",
      "A closure law tabulated with error control (monotone C¹ Hermite, exact tangent; "
      "first segment in √Δ). Build with from_stress/from_closure (or rockjoint.tabulate), "
      "or load().")
      // The tabulation defaults, spelled once (TabulatedLaw::Options): Python reads them here.
      .def_property_readonly_static("default_tolerance", [](py::object)
                                    { return TabulatedLaw::Options{}.tolerance; },
                                    "Default relative error bound [-] of σ and k")
      .def_property_readonly_static("default_maximum_knots", [](py::object)
                                    { return TabulatedLaw::Options{}.maximum_knots; },
                                    "Default cap on the number of knots")
      .def_static(
          "from_stress",
          [](const ClosureLaw& law, double maximum_stress, double tolerance,
             std::optional<double> residual_stiffness, std::size_t maximum_knots)
          {
            const auto o = options(tolerance, residual_stiffness, maximum_knots);
            py::gil_scoped_release release;
            return std::make_shared<TabulatedLaw>(
                TabulatedLaw::up_to_stress(law, maximum_stress, o));
          },
          py::arg("law"), py::arg("maximum_stress"), py::arg("tolerance") = TabulatedLaw::Options{}.tolerance,
          py::arg("residual_stiffness") = py::none(),
          py::arg("maximum_knots") = TabulatedLaw::Options{}.maximum_knots,
          "Tabulate `law` up to σ_max [Pa] (Δ_max = law.closure_at_stress(σ_max)); relative "
          "error of σ and k <= tolerance; residual_stiffness k_res [Pa/m] (None: 1e-6 "
          "σ_max/Δ_max, 0: strict σ = k = 0 when open)")
      .def_static(
          "from_closure",
          [](const ClosureLaw& law, double maximum_closure, double tolerance,
             std::optional<double> residual_stiffness, std::size_t maximum_knots)
          {
            const auto o = options(tolerance, residual_stiffness, maximum_knots);
            py::gil_scoped_release release;
            return std::make_shared<TabulatedLaw>(
                TabulatedLaw::over_closure_range(law, maximum_closure, o));
          },
          py::arg("law"), py::arg("maximum_closure"), py::arg("tolerance") = TabulatedLaw::Options{}.tolerance,
          py::arg("residual_stiffness") = py::none(),
          py::arg("maximum_knots") = TabulatedLaw::Options{}.maximum_knots,
          "Tabulate `law` over closures [0, Δ_max] [m] (Δ_max < law.maximum_closure)")
      .def_static(
          "load",
          [](const std::string& path)
          {
            return file_errors_as_value_errors(
                [&] { return std::make_shared<TabulatedLaw>(TabulatedLaw::load(path)); });
          },
          py::arg("path"),
          "Read a .rjt table file; ValueError naming the file, line and field if malformed")
      .def(
          "save",
          [](const TabulatedLaw& law, const std::string& path)
          { file_errors_as_value_errors([&] { law.save(path); }); },
          py::arg("path"), "Write the table (bit-exact round trip)")
      .def("evaluate", &evaluate_to_numpy<TabulatedLaw>, py::arg("closure"),
           "(σ [Pa], k [Pa/m], A/A0 (0), status) with the residual stiffness when open")
      .def("normal_stress", &evaluate_column<0, TabulatedLaw>, py::arg("closure"), "σ(Δ) [Pa]")
      .def("normal_stiffness", &evaluate_column<1, TabulatedLaw>, py::arg("closure"), "k(Δ) [Pa/m]")
      .def("contact_area_ratio", &evaluate_column<2, TabulatedLaw>, py::arg("closure"), "0: no area model")
      .def_property_readonly("knot_closure",
                             [](const TabulatedLaw& t) { return to_numpy(t.table().closure); },
                             "Knots Δ_i [m] (Δ_0 = 0)")
      .def_property_readonly("knot_stress",
                             [](const TabulatedLaw& t) { return to_numpy(t.table().normal_stress); },
                             "σ_i at the knots [Pa]")
      .def_property_readonly("knot_stiffness",
                             [](const TabulatedLaw& t) { return to_numpy(t.table().stiffness); },
                             "k_i = dσ/dΔ at the knots [Pa/m] (monotone-limited; k_0 = k(0+))")
      .def_property_readonly("tolerance", [](const TabulatedLaw& t) { return t.table().tolerance; },
                             "Relative error bound [-] of σ and k the table was built to")
      .def_property_readonly("checked_error_stress",
                             [](const TabulatedLaw& t) { return t.table().checked_error_stress; },
                             "Largest relative σ error the builder found at its check points")
      .def_property_readonly("checked_error_stiffness",
                             [](const TabulatedLaw& t) { return t.table().checked_error_stiffness; },
                             "Largest relative k error the builder found at its check points")
      .def_property_readonly("residual_stiffness", &TabulatedLaw::residual_stiffness,
                             "k_res [Pa/m] for Δ <= 0")
      .def_property_readonly("initial_stiffness",
                             [](const TabulatedLaw& t) { return t.table().stiffness[0]; },
                             "k(0+) [Pa/m]: 0 for a Hertzian onset")
      .def_property_readonly("table_maximum_closure", &TabulatedLaw::table_maximum_closure,
                             "Δ_max [m] (last knot)")
      .def_property_readonly("table_maximum_stress", &TabulatedLaw::table_maximum_stress,
                             "σ_max [Pa] (last knot)")
      .def_property_readonly("table_end_stiffness", &TabulatedLaw::table_end_stiffness,
                             "k at Δ_max [Pa/m], the slope of the linear extension")
      .def_property_readonly("knot_count", &TabulatedLaw::knot_count, "Number of knots")
      .def_property_readonly("memory_bytes", &TabulatedLaw::memory_bytes,
                             "Bytes the law takes in memory: the object, its Hermite segments, cell index and knots")
      .def_property_readonly("law_evaluations", &TabulatedLaw::law_evaluations,
                             "Source-law calls of the build (0 if loaded)")
      .def_property_readonly("source_model",
                             [](const TabulatedLaw& t) { return t.table().source_model; },
                             "Model name of the tabulated law (ClosureLaw.name)")
      .def_property_readonly("source_parameters",
                             [](const TabulatedLaw& t) { return t.table().source_parameters; },
                             "Parameters of the tabulated law (a list of Parameter)")
      .def_property_readonly("source_seating_stress",
                             [](const TabulatedLaw& t) { return t.table().source_seating_stress; },
                             "Seating stress [Pa] of the tabulated law")
      .def("__repr__",
           [](const TabulatedLaw& t)
           {
             return "<TabulatedLaw of " + t.table().source_model + ": "
                    + std::to_string(t.knot_count()) + " knots, tolerance "
                    + py::str(py::float_(t.table().tolerance)).cast<std::string>() + ">";
           });
}

void declare_constitutive(py::module_& m)
{
  declare_laws(m);
  declare_asperity_models(m);
  declare_tang_jiao(m);
  declare_tabulation(m);
}
} // namespace rockjoint::python
