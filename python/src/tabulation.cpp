// Bindings of rockjoint::constitutive::TabulatedLaw. The Python layer
// (rockjoint/tabulation.py) owns the defaults and the plotting; this file exposes the table,
// its knots as numpy arrays and the file format.
#include "array_helpers.hpp"

#include <rockjoint/constitutive/tabulated_law.hpp>

#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace py = pybind11;
using namespace rockjoint::constitutive;

namespace rockjoint::python
{

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
          py::arg("law"), py::arg("maximum_stress"), py::arg("tolerance") = 1e-6,
          py::arg("residual_stiffness") = py::none(), py::arg("maximum_knots") = 20000,
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
          py::arg("law"), py::arg("maximum_closure"), py::arg("tolerance") = 1e-6,
          py::arg("residual_stiffness") = py::none(), py::arg("maximum_knots") = 20000,
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
      .def_property_readonly("tolerance", [](const TabulatedLaw& t) { return t.table().tolerance; })
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
      .def_property_readonly("knot_count", &TabulatedLaw::knot_count)
      .def_property_readonly("memory_bytes", &TabulatedLaw::memory_bytes)
      .def_property_readonly("law_evaluations", &TabulatedLaw::law_evaluations,
                             "Source-law calls of the build (0 if loaded)")
      .def_property_readonly("source_model",
                             [](const TabulatedLaw& t) { return t.table().source_model; })
      .def_property_readonly("source_parameters",
                             [](const TabulatedLaw& t) { return t.table().source_parameters; })
      .def_property_readonly("source_seating_stress",
                             [](const TabulatedLaw& t) { return t.table().source_seating_stress; })
      .def("__repr__",
           [](const TabulatedLaw& t)
           {
             return "<TabulatedLaw of " + t.table().source_model + ": "
                    + std::to_string(t.knot_count()) + " knots, tolerance "
                    + py::str(py::float_(t.table().tolerance)).cast<std::string>() + ">";
           });
}

} // namespace rockjoint::python
