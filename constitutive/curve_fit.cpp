// SPDX-License-Identifier: MIT
#include "curve_fit.hpp"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive::calibration
{

namespace
{
/// What the GSL callback needs, and where it leaves a model exception.
struct Context
{
  const CurveModel* model;
  std::span<const double> observed;
  std::size_t parameters;
  std::exception_ptr error;
};

/// f_i = m_i(p) - y_i (GSL applies √w_i itself). A throwing model stops the fit: the
/// exception is kept and GSL gets GSL_EBADFUNC, which ends gsl_multifit_nlinear_driver.
int residual(const gsl_vector* x, void* data, gsl_vector* f)
{
  auto* c = static_cast<Context*>(data);
  if (c->error)
    return GSL_EBADFUNC;
  std::vector<double> p(c->parameters), m(c->observed.size());
  for (std::size_t j = 0; j < c->parameters; ++j)
    p[j] = gsl_vector_get(x, j);
  try
  {
    (*c->model)(p, m);
  }
  catch (...)
  {
    c->error = std::current_exception();
    return GSL_EBADFUNC;
  }
  for (std::size_t i = 0; i < m.size(); ++i)
  {
    if (!std::isfinite(m[i]))
      return GSL_EBADFUNC;
    gsl_vector_set(f, i, m[i] - c->observed[i]);
  }
  return GSL_SUCCESS;
}

struct WorkspaceDeleter
{
  void operator()(gsl_multifit_nlinear_workspace* w) const { gsl_multifit_nlinear_free(w); }
};
struct MatrixDeleter
{
  void operator()(gsl_matrix* m) const { gsl_matrix_free(m); }
};

void require_finite(std::span<const double> v, const char* name)
{
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
    {
      std::ostringstream msg;
      msg << "fit_curve: " << name << "[" << i << "] = " << v[i] << " is not finite";
      throw std::invalid_argument(msg.str());
    }
}
} // namespace

CurveFitResult fit_curve(const CurveModel& model, std::span<const double> observed,
                         std::span<const double> initial, std::span<const double> weights,
                         const CurveFitOptions& options)
{
  const std::size_t n = observed.size(), p = initial.size();
  if (!model)
    throw std::invalid_argument("fit_curve: the model is empty");
  if (p == 0)
    throw std::invalid_argument("fit_curve: no parameters to fit");
  if (n <= p)
    throw std::invalid_argument("fit_curve: " + std::to_string(n) + " observations for "
                                + std::to_string(p)
                                + " parameters; more observations than parameters are needed");
  if (!weights.empty() && weights.size() != n)
    throw std::invalid_argument("fit_curve: " + std::to_string(weights.size()) + " weights for "
                                + std::to_string(n) + " observations; they must match");
  require_finite(observed, "observed");
  require_finite(initial, "initial");
  require_finite(weights, "weights");
  double weight_sum = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    if (weights[i] < 0.0)
      throw std::invalid_argument("fit_curve: weights[" + std::to_string(i)
                                  + "] is negative; weights must be >= 0");
    weight_sum += weights[i];
  }
  if (!weights.empty() && !(weight_sum > 0.0))
    throw std::invalid_argument("fit_curve: all weights are zero");
  if (options.maximum_iterations < 1)
    throw std::invalid_argument("fit_curve: maximum_iterations must be >= 1");

  // GSL's abort-on-error handler off for this call (project rule: codes become statuses).
  gsl_error_handler_t* previous = gsl_set_error_handler_off();
  struct Restore
  {
    gsl_error_handler_t* h;
    ~Restore() { gsl_set_error_handler(h); }
  } restore{previous};

  Context context{&model, observed, p, nullptr};
  gsl_multifit_nlinear_fdf fdf;
  fdf.f = residual;
  fdf.df = nullptr; // forward-difference Jacobian (GSL)
  fdf.fvv = nullptr;
  fdf.n = n;
  fdf.p = p;
  fdf.params = &context;

  gsl_multifit_nlinear_parameters settings = gsl_multifit_nlinear_default_parameters();
  settings.trs = gsl_multifit_nlinear_trs_lm;
  settings.scale = gsl_multifit_nlinear_scale_more;
  std::unique_ptr<gsl_multifit_nlinear_workspace, WorkspaceDeleter> work(
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &settings, n, p));
  if (!work)
    throw std::runtime_error("fit_curve: GSL could not allocate the workspace");

  gsl_vector_const_view x0 = gsl_vector_const_view_array(initial.data(), p);
  int status;
  if (weights.empty())
    status = gsl_multifit_nlinear_init(&x0.vector, &fdf, work.get());
  else
  {
    gsl_vector_const_view w = gsl_vector_const_view_array(weights.data(), n);
    status = gsl_multifit_nlinear_winit(&x0.vector, &w.vector, &fdf, work.get());
  }
  if (context.error)
    std::rethrow_exception(context.error);
  if (status != GSL_SUCCESS)
    throw std::invalid_argument("fit_curve: the model is not finite at the initial parameters");

  int info = 0;
  status = gsl_multifit_nlinear_driver(static_cast<std::size_t>(options.maximum_iterations),
                                       options.step_tolerance, options.gradient_tolerance, 0.0,
                                       nullptr, nullptr, &info, work.get());
  if (context.error)
    std::rethrow_exception(context.error);

  CurveFitResult r;
  r.converged = status == GSL_SUCCESS;
  // GSL reports "no step reduced χ² on the first iteration" as GSL_EMAXITER with
  // info = GSL_ENOPROG: the start is already a minimum to rounding (e.g. exact data and an
  // exact initial guess) or the problem is degenerate; χ² decides which (below).
  const bool stuck_at_start = status == GSL_EMAXITER && info == GSL_ENOPROG;
  if (status == GSL_SUCCESS)
    r.message = info == 1 ? "converged: small step" : "converged: small gradient";
  else if (stuck_at_start)
    r.message = "no step reduced χ² from the initial parameters";
  else if (status == GSL_EMAXITER)
    r.message = "stopped: iteration limit reached";
  else if (status == GSL_ENOPROG)
    r.message = "stopped: no further progress (the minimum is flat or ill-conditioned)";
  else
    r.message = std::string("stopped: ") + gsl_strerror(status);

  const gsl_vector* x = gsl_multifit_nlinear_position(work.get());
  const gsl_vector* f = gsl_multifit_nlinear_residual(work.get()); // √w_i (m_i - y_i)
  r.parameters.resize(p);
  for (std::size_t j = 0; j < p; ++j)
    r.parameters[j] = gsl_vector_get(x, j);
  gsl_blas_ddot(f, f, &r.chi_squared);
  r.degrees_of_freedom = static_cast<int>(n - p);
  r.iterations = static_cast<int>(gsl_multifit_nlinear_niter(work.get()));
  r.function_evaluations = static_cast<int>(work->fdf->nevalf);
  if (stuck_at_start)
  {
    // Converged if the start fits the data to rounding: χ² <= (1e-10)² Σ w y².
    double scale = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      scale += (weights.empty() ? 1.0 : weights[i]) * observed[i] * observed[i];
    r.converged = r.chi_squared <= 1e-20 * scale;
    r.message += r.converged ? ": they fit the data to rounding (converged)"
                             : ": the minimum is flat or the problem degenerate";
  }

  // Unweighted residuals at the minimum, from the model itself.
  r.residuals.resize(n);
  model(r.parameters, r.residuals);
  for (std::size_t i = 0; i < n; ++i)
    r.residuals[i] -= observed[i];

  // C = s² (JᵀWJ)⁻¹ with the (weighted) Jacobian at the minimum; s² = χ²/(N-P).
  std::unique_ptr<gsl_matrix, MatrixDeleter> covariance(gsl_matrix_alloc(p, p));
  gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(work.get()), 0.0, covariance.get());
  const double variance = r.chi_squared / r.degrees_of_freedom;
  r.covariance.resize(p * p);
  r.standard_errors.resize(p);
  for (std::size_t i = 0; i < p; ++i)
  {
    for (std::size_t j = 0; j < p; ++j)
      r.covariance[i * p + j] = variance * gsl_matrix_get(covariance.get(), i, j);
    // GSL zeroes the row and column of a parameter whose Jacobian column depends on the others
    // (here: is zero to rounding, e.g. a log-parameter driven to where it no longer changes the
    // model): the data do not determine it, so its uncertainty is unbounded, not zero.
    const bool determined = gsl_matrix_get(covariance.get(), i, i) > 0.0 || variance == 0.0;
    r.standard_errors[i] = determined ? std::sqrt(r.covariance[i * p + i])
                                      : std::numeric_limits<double>::infinity();
  }
  return r;
}

} // namespace rockjoint::constitutive::calibration
