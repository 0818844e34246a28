// SPDX-License-Identifier: MIT
#include "closure_law.hpp"
#include "root_finding.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive
{

const char* to_string(Status status)
{
  switch (status)
  {
  case Status::contact: return "contact";
  case Status::open: return "open";
  case Status::validity_limit: return "validity_limit";
  case Status::beyond_maximum_closure: return "beyond_maximum_closure";
  case Status::invalid_closure: return "invalid_closure";
  case Status::quadrature_not_converged: return "quadrature_not_converged";
  }
  return "unknown";
}

ClosureResponse ClosureLaw::evaluate(double closure) const
{
  if (std::isnan(closure))
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, Status::invalid_closure};
  }
  if (closure <= 0.0)
    return evaluate_open(closure);
  return evaluate_contact(closure);
}

HistoryResponse ClosureLaw::evaluate_with_history(double closure, double maximum_closure) const
{
  HistoryResponse h;
  if (std::isnan(closure) || std::isnan(maximum_closure))
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    h.response = {nan, nan, nan, nan, Status::invalid_closure};
    h.maximum_closure = h.permanent_closure = nan;
    return h;
  }
  h.response = evaluate(closure);
  h.maximum_closure = std::max({maximum_closure, closure, 0.0});
  return h;
}

ClosureResponse ClosureLaw::beyond_maximum_closure(double contact_area_ratio)
{
  const double inf = std::numeric_limits<double>::infinity();
  return {inf, inf, contact_area_ratio, 0.0, Status::beyond_maximum_closure};
}

void ClosureLaw::evaluate(std::span<const double> closure, std::span<double> normal_stress,
                          std::span<double> normal_stiffness, std::span<double> area_ratio,
                          std::span<Status> status) const
{
  check_batch_sizes("ClosureLaw::evaluate", closure, normal_stress, normal_stiffness,
                    area_ratio, status);
  const std::size_t n = closure.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const ClosureResponse r = evaluate(closure[i]);
    normal_stress[i] = r.normal_stress;
    normal_stiffness[i] = r.normal_stiffness;
    if (!area_ratio.empty())
      area_ratio[i] = r.contact_area_ratio;
    if (!status.empty())
      status[i] = r.status;
  }
}

void ClosureLaw::check_batch_sizes(const char* who, std::span<const double> closure,
                                   std::span<double> normal_stress,
                                   std::span<double> normal_stiffness,
                                   std::span<double> area_ratio, std::span<Status> status)
{
  const std::size_t n = closure.size();
  if (normal_stress.size() != n || normal_stiffness.size() != n
      || (!area_ratio.empty() && area_ratio.size() != n)
      || (!status.empty() && status.size() != n))
  {
    throw std::invalid_argument(std::string(who)
                                + ": output arrays must have the size of the closure array ("
                                + std::to_string(n) + ")");
  }
}

void ClosureLaw::check_target_stress(double target) const
{
  if (!(target >= 0.0) || std::isinf(target))
  {
    std::ostringstream msg;
    msg << name() << ": normal stress " << target
        << " Pa has no closure; it must be finite and >= 0";
    throw std::invalid_argument(msg.str());
  }
}

double ClosureLaw::closure_at_stress(double target) const
{
  check_target_stress(target);
  if (target == 0.0)
    return 0.0;

  // Bracket [lo, hi] with σ(lo) < target <= σ(hi).
  const double dmax = maximum_closure();
  double lo = 0.0;
  double hi = std::isfinite(dmax) ? 0.5 * dmax : 1e-6;
  ClosureResponse rhi = evaluate(hi);
  for (int it = 0; rhi.normal_stress < target; ++it)
  {
    if (rhi.status == Status::validity_limit || rhi.status == Status::beyond_maximum_closure
        || it > 2000)
    {
      std::ostringstream msg;
      msg << name() << ": normal stress " << target
          << " Pa is beyond the law's admissible range (maximum closure " << dmax << " m)";
      throw std::domain_error(msg.str());
    }
    lo = hi;
    hi = root_finding::grow_towards(hi, dmax);
    rhi = evaluate(hi);
  }

  // Safeguarded Newton on r(Δ) = σ(Δ) - target, from the upper end of the bracket.
  const root_finding::Root root = root_finding::find_root(
      [&](double x)
      {
        const ClosureResponse r = x == hi ? rhi : evaluate(x);
        return root_finding::Residual{r.normal_stress - target, r.normal_stiffness};
      },
      lo, hi, hi);
  return root.x;
}

} // namespace rockjoint::constitutive
