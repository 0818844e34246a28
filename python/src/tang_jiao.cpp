// Bindings of the Tang & Jiao (2018) law and its interaction cell (closed form and the
// paper's algorithm). C++ errors become ValueError (std::invalid_argument, std::domain_error).
#include "array_helpers.hpp"

#include <rockjoint/constitutive/asperity_parameters.hpp>
#include <rockjoint/constitutive/interaction_cell.hpp>
#include <rockjoint/constitutive/interaction_cell_numeric.hpp>
#include <rockjoint/constitutive/tang_jiao.hpp>

#include <pybind11/stl.h>

#include <optional>
#include <string>

namespace py = pybind11;
using namespace rockjoint::constitutive;

namespace rockjoint::python
{

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
                             { return l.variant() == TangJiaoVariant::kinematic ? "I2" : "I1"; })
      .def_property_readonly("limit", &TangJiao::limit)
      .def_property_readonly("limit_description", &TangJiao::limit_description)
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
      .def_property_readonly("territory_radius", &interaction_cell::Cell::territory_radius)
      .def_property_readonly("mean_pressure", &interaction_cell::Cell::mean_pressure)
      .def_property_readonly("local_approach", &interaction_cell::Cell::local_approach)
      .def_property_readonly("hertz_load", &interaction_cell::Cell::hertz_load)
      .def_property_readonly("interaction_load", &interaction_cell::Cell::interaction_load)
      .def_property_readonly("load", &interaction_cell::Cell::load)
      .def_property_readonly("closure_shift", &interaction_cell::Cell::closure_shift)
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
                             { return c.solution().mean_pressure; })
      .def_property_readonly("local_approach",
                             [](const interaction_cell::NumericCell& c)
                             { return c.solution().local_approach; })
      .def_property_readonly("load", [](const interaction_cell::NumericCell& c)
                             { return c.solution().load; })
      .def_property_readonly("iterations",
                             [](const interaction_cell::NumericCell& c)
                             {
                               return py::make_tuple(c.solution().outer_iterations,
                                                     c.solution().inner_iterations);
                             })
      .def_property_readonly("converged", [](const interaction_cell::NumericCell& c)
                             { return c.solution().converged; })
      .def(
          "pressure",
          [](const interaction_cell::NumericCell& c, const DoubleArray& r)
          { return py::vectorize([&c](double x) { return c.pressure(x); })(r); },
          py::arg("r"), "p(r) [Pa] at radius r [m]");
}

} // namespace rockjoint::python
