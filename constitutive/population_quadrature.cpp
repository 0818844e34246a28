// SPDX-License-Identifier: MIT
#include "population_quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <vector>

namespace rockjoint::constitutive::quadrature
{

namespace
{
/// Subintervals of the adaptive rule: the integrands are smooth after the substitution and
/// converge in a handful of bisections; 200 leaves room for sharp peaks (large separations).
constexpr std::size_t max_intervals = 200;

struct QagWorkspace
{
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(max_intervals);
  ~QagWorkspace() { gsl_integration_workspace_free(w); }
};

struct CquadWorkspace
{
  gsl_integration_cquad_workspace* w = gsl_integration_cquad_workspace_alloc(200);
  ~CquadWorkspace() { gsl_integration_cquad_workspace_free(w); }
};
} // namespace

void disable_gsl_abort()
{
  static std::once_flag flag;
  std::call_once(flag, [] { gsl_set_error_handler_off(); });
}

Result integrate(const gsl_function& f, double a, double b, double tolerance)
{
  if (!(b > a))
    return {};
  disable_gsl_abort();
  const double rel = std::max(tolerance, minimum_tolerance);
  // Workspaces per thread (laws are const and may be evaluated concurrently) and per nesting
  // level (an integrand may itself evaluate a law that integrates).
  thread_local std::vector<std::unique_ptr<QagWorkspace>> qag_pool;
  thread_local std::vector<std::unique_ptr<CquadWorkspace>> cquad_pool;
  thread_local std::size_t depth = 0;
  struct Nesting
  {
    std::size_t& d;
    explicit Nesting(std::size_t& d_) : d(d_) { ++d; }
    ~Nesting() { --d; }
  } nesting(depth);
  const std::size_t level = depth - 1;
  if (qag_pool.size() <= level)
    qag_pool.push_back(std::make_unique<QagWorkspace>());
  Result r;
  gsl_function fn = f;
  int status = gsl_integration_qag(&fn, a, b, 0.0, rel, max_intervals, GSL_INTEG_GAUSS61,
                                   qag_pool[level]->w, &r.value, &r.error);
  if (status == GSL_SUCCESS && std::isfinite(r.value))
    return r;

  while (cquad_pool.size() <= level)
    cquad_pool.push_back(std::make_unique<CquadWorkspace>());
  Result alt;
  std::size_t evaluations = 0;
  status = gsl_integration_cquad(&fn, a, b, 0.0, rel, cquad_pool[level]->w, &alt.value, &alt.error,
                                 &evaluations);
  // CQUAD reports success whenever its input is valid: judge it by its error estimate.
  if (status == GSL_SUCCESS && std::isfinite(alt.value) && alt.error <= rel * std::abs(alt.value))
    return alt;
  // Neither met the tolerance: keep the better estimate.
  Result best = (std::isfinite(alt.value) && !(alt.error >= r.error)) ? alt : r;
  best.converged = false;
  return best;
}

} // namespace rockjoint::constitutive::quadrature
