// SPDX-License-Identifier: MIT
#include "closure_parameters.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::topography
{

namespace validation = rockjoint::constitutive::validation;

constitutive::AsperityParameters asperity_parameters(const SummitStatistics& s,
                                                     double composite_modulus)
{
  validation::positive("asperity_parameters", "composite_modulus", composite_modulus, "Pa");
  if (s.summit_count < 2)
  {
    std::ostringstream msg;
    msg << "asperity_parameters: the surface has " << s.summit_count
        << " summit(s); at least 2 are needed for a summit-height std (identical walls in a "
           "mated state have none: zero closure capacity)";
    throw std::invalid_argument(msg.str());
  }
  return {composite_modulus, s.summit_density, s.summit_radius, s.summit_height_std,
          std::max(s.sampling_interval_x, s.sampling_interval_y)};
}

constitutive::AsperityParameters asperity_parameters(const NayakEstimates& e,
                                                     double composite_modulus)
{
  const constitutive::AsperityParameters p{composite_modulus, e.summit_density, e.summit_radius,
                                           e.summit_height_std, e.sampling_interval};
  constitutive::validate(p, "asperity_parameters (spectral)");
  return p;
}

std::vector<ResamplingRow> resampling_study(const Surface& surface,
                                            const std::vector<int>& factors)
{
  std::vector<ResamplingRow> rows;
  for (int f : factors)
  {
    const Surface s = f == 1 ? surface : decimate(surface, f);
    const double h = std::max(s.spacing_x(), s.spacing_y());
    rows.push_back({f, h, analyse_summits(s).statistics,
                    nayak_estimates(finite_difference_moments(s), h)});
  }
  return rows;
}

} // namespace rockjoint::topography
