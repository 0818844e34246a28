// Bindings of rockjoint::constitutive. Laws are held by shared_ptr so that composite laws
// (Tang & Jiao over a GW base, tables over any law) can share them.
#include "array_helpers.hpp"

#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/closure_law.hpp>
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/hertz.hpp>

#include <pybind11/stl.h>

namespace py = pybind11;
using namespace rockjoint::constitutive;

namespace rockjoint::python
{

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

void declare_constitutive(py::module_& m)
{
  py::enum_<Status>(m, "Status", "Outcome of one law evaluation")
      .value("contact", Status::contact)
      .value("open", Status::open)
      .value("validity_limit", Status::validity_limit)
      .value("beyond_maximum_closure", Status::beyond_maximum_closure)
      .value("invalid_closure", Status::invalid_closure)
      .value("quadrature_not_converged", Status::quadrature_not_converged);

  py::class_<Parameter>(m, "Parameter")
      .def_readonly("name", &Parameter::name)
      .def_readonly("value", &Parameter::value)
      .def_readonly("unit", &Parameter::unit)
      .def("__repr__", [](const Parameter& p)
           { return p.name + "=" + std::to_string(p.value) + " " + p.unit; });

  py::class_<ClosureLaw, std::shared_ptr<ClosureLaw>>(
      m, "ClosureLaw", "Normal-closure law σ(Δ) of a rough joint (SI: Pa, m)")
      .def_property_readonly("name", &ClosureLaw::name)
      .def_property_readonly("parameters", &ClosureLaw::parameters)
      .def_property_readonly("provides_contact_area", &ClosureLaw::provides_contact_area)
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
           "Inverse Δ(σ) [m] for σ >= 0 [Pa]");

  py::class_<BartonBandis, ClosureLaw, std::shared_ptr<BartonBandis>>(
      m, "BartonBandis", "Barton-Bandis hyperbola σ = K_ni Δ / (1 - Δ/V_m)")
      .def(py::init<double, double>(), py::arg("initial_normal_stiffness"),
           py::arg("maximum_closure"))
      .def_static(
          "from_joint_properties",
          [](double jrc, double jcs, double aj)
          { return std::make_shared<BartonBandis>(BartonBandis::from_joint_properties(jrc, jcs, aj)); },
          py::arg("jrc"), py::arg("jcs"), py::arg("initial_aperture"),
          "Bandis et al. (1983) estimates from JRC [-], JCS [Pa], initial aperture [m]")
      .def_property_readonly("initial_normal_stiffness", &BartonBandis::initial_normal_stiffness);

  py::class_<LogarithmicLaw, ClosureLaw, std::shared_ptr<LogarithmicLaw>>(
      m, "LogarithmicLaw", "Δ = B ln(σ_t/σ0); returns σ = σ_t - σ0")
      .def(py::init<double, double>(), py::arg("closure_scale"), py::arg("seating_stress"));

  py::class_<ExponentialLaw, ClosureLaw, std::shared_ptr<ExponentialLaw>>(
      m, "ExponentialLaw", "Δ = V_m (1 - exp(-σ/σ_c))")
      .def(py::init<double, double>(), py::arg("maximum_closure"),
           py::arg("characteristic_stress"));

  m.def("composite_modulus", py::overload_cast<double, double>(&composite_modulus),
        py::arg("young"), py::arg("poisson"), "E* = E / (2(1-ν²)) [Pa] of two walls of one rock");
  m.def("composite_modulus",
        py::overload_cast<double, double, double, double>(&composite_modulus), py::arg("young1"),
        py::arg("poisson1"), py::arg("young2"), py::arg("poisson2"),
        "1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 [Pa]");
}

} // namespace rockjoint::python
