// SPDX-License-Identifier: MIT
// Bindings of rockjoint::flow: the joint's transmissivity from an aperture field, and T as a
// function of closure (SI units). The Python layer rockjoint/flow.py owns the result object,
// the defaults and the transmissivity laws.
#include "array_helpers.hpp"

#include <rockjoint/flow/reynolds_flow.hpp>
#include <rockjoint/flow/transmissivity_table.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace rockjoint::python
{
using namespace rockjoint::flow;

void declare_flow(py::module_& m)
{
  py::enum_<Boundary>(m, "Boundary", "Edges of the aperture grid (flow/reynolds_flow.hpp)")
      .value("periodic", Boundary::periodic)
      .value("sealed_sides", Boundary::sealed_sides);
  py::enum_<LinearSolver>(m, "LinearSolver", "Solver of the pressure system")
      .value("cholesky", LinearSolver::cholesky)
      .value("simplicial_cholesky", LinearSolver::simplicial_cholesky)
      .value("conjugate_gradient", LinearSolver::conjugate_gradient);

  py::class_<FlowResult>(m, "FlowResult", "Transmissivity of one aperture field (SI)")
      .def_property_readonly(
          "transmissivity",
          [](const FlowResult& r)
          {
            py::array_t<double> t({2, 2});
            std::copy(r.transmissivity.begin(), r.transmissivity.end(), t.mutable_data());
            return t;
          },
          "T [m³] (2 x 2): mean flux per unit width = -(T/μ) ∇p̄")
      .def_readonly("mechanical_aperture", &FlowResult::mechanical_aperture, "mean e [m]")
      .def_readonly("open_fraction", &FlowResult::open_fraction, "scanned points with e > 0 [-]")
      .def_readonly("percolates", &FlowResult::percolates, "an open path along (x, y)")
      .def_readonly("iterations", &FlowResult::iterations, "CG iterations per gradient")
      .def_readonly("relative_residual", &FlowResult::relative_residual, "largest |A p - b| / |b| of the pressure systems solved (0 if none was solved)")
      .def_readonly("converged", &FlowResult::converged, "every system met the tolerance (a direct solve: its factorisation)")
      .def_readonly("direct_fallback", &FlowResult::direct_fallback,
                    "CG did not converge and the supernodal factorisation solved the system")
      .def_readonly("unknowns", &FlowResult::unknowns, "pressure unknowns of the (largest) system");

  py::class_<ReynoldsFlow>(m, "ReynoldsFlow",
                           "The flow problem of one grid: transmissivity of its aperture fields")
      .def(py::init(
               [](std::size_t rows, std::size_t cols, double spacing_x, double spacing_y,
                  Boundary boundary, LinearSolver solver, double tolerance, int maximum_iterations)
               {
                 FlowOptions options;
                 options.solver = solver;
                 options.tolerance = tolerance;
                 options.maximum_iterations = maximum_iterations;
                 return ReynoldsFlow(rows, cols, spacing_x, spacing_y, boundary, options);
               }),
           py::arg("rows"), py::arg("cols"), py::arg("spacing_x"), py::arg("spacing_y"),
           py::arg("boundary"), py::arg("solver"), py::arg("tolerance"),
           py::arg("maximum_iterations"))
      .def(
          "transmissivity",
          [](ReynoldsFlow& f, const DoubleArray& aperture)
          {
            if (aperture.ndim() != 2 || std::size_t(aperture.shape(0)) != f.rows()
                || std::size_t(aperture.shape(1)) != f.cols())
              throw py::value_error("transmissivity: the aperture field must be a "
                                    + std::to_string(f.rows()) + " x " + std::to_string(f.cols())
                                    + " array (the grid's rows, cols)");
            py::gil_scoped_release release;
            return f.transmissivity(as_span(aperture));
          },
          py::arg("aperture"), "FlowResult of an aperture field e [m] (rows x cols, NaN = masked)");

  py::class_<TransmissivityTable>(m, "TransmissivityTable",
                                  "T(Δ) through (Δ_i, T_i): monotone Hermite in -ln T")
      .def(py::init(
               [](const DoubleArray& closure, const DoubleArray& transmissivity)
               { return TransmissivityTable(as_span(closure), as_span(transmissivity)); }),
           py::arg("closure"), py::arg("transmissivity"))
      .def(
          "transmissivity",
          [](const TransmissivityTable& t, const DoubleArray& closure) -> py::object
          {
            DoubleArray out = empty_like(closure);
            t.transmissivity(as_span(closure), {out.mutable_data(), std::size_t(out.size())});
            if (closure.ndim() == 0)
              return out.attr("item")();
            return out;
          },
          py::arg("closure"), "T [m³] at closure(s) Δ [m]")
      .def_property_readonly("closures", &TransmissivityTable::closures, "Knots Δ_i [m].")
      .def_property_readonly("transmissivities", &TransmissivityTable::transmissivities, "T_i [m³] at the knots.");
}

} // namespace rockjoint::python
