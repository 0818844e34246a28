// SPDX-License-Identifier: MIT
#pragma once
/// @file curve_fit.hpp
/// Weighted nonlinear least squares by Levenberg-Marquardt (GSL gsl_multifit_nlinear, trust
/// region with the LM step, forward-difference Jacobian): the engine of the calibration of a
/// closure law to a measured closure curve (docs/theory.md §9, python/rockjoint/calibration.py).
///
/// Problem: minimise χ²(p) = Σ_i w_i (m_i(p) - y_i)² over p ∈ R^P, with m(p) ∈ R^N the model's
/// predictions of the observations y. Standard uncertainties come from the linearised
/// covariance at the minimum, scaled by the residual variance (the weights are relative):
///     C = s² (Jᵀ W J)⁻¹,   s² = χ²/(N - P),
/// the usual estimate when the data's absolute noise level is unknown (it is then estimated
/// from the scatter about the fit). The model works in whatever parametrisation the caller
/// chooses (the calibration fits logarithms of positive parameters, so the search space is all
/// of R^P); C is in that parametrisation.

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rockjoint::constitutive::calibration
{

/// Predictions m(p): writes N values for the P parameters. It may throw; the fit then stops
/// and rethrows the exception (the model is never called again).
using CurveModel
    = std::function<void(std::span<const double> parameters, std::span<double> prediction)>;

/// Stopping rules and limits (GSL's test: |δp_j| <= step_tolerance (|p_j| + step_tolerance),
/// or ‖g‖∞ <= gradient_tolerance).
struct CurveFitOptions
{
  int maximum_iterations = 500; ///< iteration limit, > 0
  double step_tolerance = 1e-12; ///< relative step at which the fit stops [-]
  double gradient_tolerance = 1e-14; ///< gradient norm at which the fit stops
};

/// Outcome of a fit.
struct CurveFitResult
{
  std::vector<double> parameters;      ///< p at the minimum
  std::vector<double> covariance;      ///< C = s²(JᵀWJ)⁻¹, P×P row-major
  std::vector<double> standard_errors; ///< √C_jj; +inf for a parameter the data do not determine
  std::vector<double> residuals;       ///< m_i(p) - y_i (unweighted)
  double chi_squared = 0.0;            ///< Σ w_i (m_i - y_i)²
  int degrees_of_freedom = 0;          ///< N - P
  int iterations = 0; ///< Levenberg-Marquardt iterations made
  int function_evaluations = 0; ///< model evaluations made
  bool converged = false; ///< a stopping test was met (false: iteration limit or no progress)
  std::string message;    ///< what stopped the iteration
};

/// Fit the model to `observed` from `initial` parameters. `weights` (w_i >= 0, finite, not all
/// zero) may be empty (all 1). Throws std::invalid_argument for inconsistent sizes, N <= P,
/// non-finite data/initial values or bad weights; rethrows what the model throws.
CurveFitResult fit_curve(const CurveModel& model, std::span<const double> observed,
                         std::span<const double> initial, std::span<const double> weights = {},
                         const CurveFitOptions& options = {});

} // namespace rockjoint::constitutive::calibration
