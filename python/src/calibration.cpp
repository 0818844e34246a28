// SPDX-License-Identifier: MIT
// Bindings of rockjoint::constitutive::calibration (curve_fit.hpp): the Levenberg-Marquardt
// engine of rockjoint.calibrate. The model is a Python callable p -> predictions.
#include <rockjoint/constitutive/curve_fit.hpp>

#include "array_helpers.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

namespace py = pybind11;
using namespace rockjoint::constitutive::calibration;

namespace rockjoint::python
{

namespace
{
py::array_t<double> to_numpy(const std::vector<double>& v)
{
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

CurveFitResult fit(const py::function& model, const DoubleArray& observed,
                   const DoubleArray& initial, const std::optional<DoubleArray>& weights,
                   int maximum_iterations, double step_tolerance, double gradient_tolerance)
{
  const std::size_t n = static_cast<std::size_t>(observed.size());
  // Python exceptions cross GSL's C frames as std::exception_ptr (curve_fit.cpp catches and
  // rethrows them), so a ValueError in the model reaches the caller unchanged.
  CurveModel wrapped = [&](std::span<const double> p, std::span<double> m)
  {
    py::array_t<double> args(static_cast<py::ssize_t>(p.size()));
    std::copy(p.begin(), p.end(), args.mutable_data());
    const DoubleArray out = py::cast<DoubleArray>(model(args));
    if (static_cast<std::size_t>(out.size()) != n)
      throw py::value_error("fit_curve: the model returned " + std::to_string(out.size())
                            + " predictions for " + std::to_string(n) + " observations");
    std::copy(out.data(), out.data() + n, m.begin());
  };
  CurveFitOptions options;
  options.maximum_iterations = maximum_iterations;
  options.step_tolerance = step_tolerance;
  options.gradient_tolerance = gradient_tolerance;
  const std::span<const double> w = weights ? as_span(*weights) : std::span<const double>{};
  return fit_curve(wrapped, as_span(observed), as_span(initial), w, options);
}
} // namespace

void declare_calibration(py::module_& m)
{
  py::class_<CurveFitResult>(m, "CurveFitResult",
                             "Outcome of a Levenberg-Marquardt fit (curve_fit.hpp)")
      .def_property_readonly("parameters",
                             [](const CurveFitResult& r) { return to_numpy(r.parameters); })
      .def_property_readonly(
          "covariance",
          [](const CurveFitResult& r)
          {
            const auto p = static_cast<py::ssize_t>(r.parameters.size());
            py::array_t<double> c({p, p});
            std::copy(r.covariance.begin(), r.covariance.end(), c.mutable_data());
            return c;
          },
          "s² (JᵀWJ)⁻¹, s² = χ²/(N-P), in the fitted parametrisation")
      .def_property_readonly("standard_errors",
                             [](const CurveFitResult& r) { return to_numpy(r.standard_errors); })
      .def_property_readonly("residuals",
                             [](const CurveFitResult& r) { return to_numpy(r.residuals); },
                             "m_i(p) - y_i (unweighted)")
      .def_readonly("chi_squared", &CurveFitResult::chi_squared, "Σ w_i (m_i - y_i)²")
      .def_readonly("degrees_of_freedom", &CurveFitResult::degrees_of_freedom, "N - P")
      .def_readonly("iterations", &CurveFitResult::iterations, "Levenberg-Marquardt iterations made")
      .def_readonly("function_evaluations", &CurveFitResult::function_evaluations, "model evaluations made")
      .def_readonly("converged", &CurveFitResult::converged, "a stopping test was met (false: iteration limit or no progress)")
      .def_readonly("message", &CurveFitResult::message, "what stopped the iteration");

  m.def("fit_curve", &fit, py::arg("model"), py::arg("observed"), py::arg("initial"),
        py::arg("weights") = py::none(), py::arg("maximum_iterations") = 500,
        py::arg("step_tolerance") = 1e-12, py::arg("gradient_tolerance") = 1e-14,
        "Weighted least squares min Σ w_i (model(p)_i - observed_i)² by Levenberg-Marquardt "
        "(GSL multifit_nlinear, finite-difference Jacobian). `model` maps a parameter array "
        "to predictions. Standard errors from the covariance scaled by the residual "
        "variance.");
}

} // namespace rockjoint::python
