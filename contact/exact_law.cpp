// SPDX-License-Identifier: MIT
#include "exact_law.hpp"

#include <rockjoint/constitutive/monotone_hermite.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::contact
{

constitutive::TabulatedLaw exact_elastic_law(std::span<const ContactState> curve,
                                             const ContactSource& source,
                                             double residual_stiffness,
                                             double initial_stiffness)
{
  namespace hermite = constitutive::hermite;
  if (curve.size() < 2)
    throw std::invalid_argument("exact_elastic_law: needs at least 2 loads, got "
                                + std::to_string(curve.size()));
  constitutive::LawTable table;
  table.source_model = "bem_elastic_contact";
  table.source_parameters = {{"composite_modulus", source.composite_modulus, "Pa"},
                             {"spacing", source.spacing, "m"},
                             {"rows", source.rows, ""},
                             {"cols", source.cols, ""},
                             {"periodic", source.kernel == Kernel::periodic ? 1.0 : 0.0, ""},
                             {"solver_tolerance", source.tolerance, ""}};
  table.tolerance = source.tolerance; // the knots are the data: no interpolation check
  table.closure.push_back(0.0);
  table.normal_stress.push_back(0.0);
  for (std::size_t i = 0; i < curve.size(); ++i)
  {
    const ContactState& s = curve[i];
    std::ostringstream at;
    at << "exact_elastic_law: load " << i << " (σ = " << s.mean_pressure << " Pa)";
    if (!s.converged)
      throw std::invalid_argument(at.str() + " did not converge");
    if (!(s.closure > table.closure.back()) || !(s.mean_pressure > table.normal_stress.back()))
      throw std::invalid_argument(at.str() + ": closure " + std::to_string(s.closure)
                                  + " m and stress must increase from the previous point");
    table.closure.push_back(s.closure);
    table.normal_stress.push_back(s.mean_pressure);
  }
  const std::size_t n = table.closure.size();
  table.stiffness.assign(n, 0.0);
  hermite::data_slopes(table.closure, table.normal_stress, table.stiffness);
  // First segment: quartic in √Δ with k(0+) = 0; it is monotone when k1 <= 2 σ1/Δ1 (its
  // cubic coefficient 4σ1 - 2Δ1 k1 >= 0). At the bound that coefficient is 0 up to rounding,
  // and a rounded -1e-16 σ1 fails hermite::first_segment_is_monotone: the cap is taken 1e-12
  // inside (a curve whose data slope exceeds it: the first load far below the second's slope).
  if (!(initial_stiffness >= 0.0
        && initial_stiffness <= curve[0].mean_pressure / curve[0].closure))
    throw std::invalid_argument("exact_elastic_law: initial_stiffness = "
                                + std::to_string(initial_stiffness)
                                + " Pa/m must be in [0, σ1/Δ1] (the secant to the first load)");
  table.stiffness[0] = initial_stiffness;
  table.stiffness[1] = std::min(table.stiffness[1], (1.0 - 1e-12) * 2.0 * table.normal_stress[1]
                                                        / table.closure[1]);
  hermite::limit_slopes(table.closure, table.normal_stress, table.stiffness);
  table.residual_stiffness = std::isnan(residual_stiffness)
                                 ? constitutive::TabulatedLaw::default_residual_stiffness_fraction
                                       * table.normal_stress.back() / table.closure.back()
                                 : residual_stiffness;
  return constitutive::TabulatedLaw(std::move(table));
}

} // namespace rockjoint::contact
