// Bindings of the GW-type asperity laws (theory §2, §4): GreenwoodWilliamson and
// TangSubstrate over a Gaussian, exponential or empirical summit-height distribution.
// Keyword arguments in SI units; C++ std::invalid_argument becomes ValueError.
#include "array_helpers.hpp"

#include <rockjoint/constitutive/asperity_parameters.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/substrate.hpp>
#include <rockjoint/constitutive/summit_population_law.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <pybind11/stl.h>

#include <optional>
#include <string>

namespace py = pybind11;
using namespace rockjoint::constitutive;

namespace rockjoint::python
{

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
                             { return std::string(to_string(l.distribution())); })
      .def_property_readonly("quadrature_tolerance", &SummitPopulationLaw::quadrature_tolerance)
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
      .def_readonly_static("CENTRE_DEFLECTION", &substrate::centre_deflection)
      .def_readonly_static("MEAN_DEFLECTION", &substrate::mean_deflection)
      .def_readonly_static("RIGID_BASE", &substrate::rigid_base);
}

} // namespace rockjoint::python
