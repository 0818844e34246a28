// SPDX-License-Identifier: MIT
#pragma once
/// @file closure_parameters.hpp
/// From a topography to the inputs of the asperity closure laws (GW, Tang, Tang & Jiao), and
/// the resampling study that shows how those inputs depend on the sampling interval.

#include "spectral_moments.hpp"
#include "summits.hpp"

#include <rockjoint/constitutive/asperity_parameters.hpp>

#include <vector>

namespace rockjoint::topography
{

/// AsperityParameters (theory §2) from counted summit statistics and a composite modulus
/// E* [Pa] (1/E* = (1-ν1²)/E1 + (1-ν2²)/E2, see constitutive/elasticity.hpp), with the
/// sampling interval h = max(h_x, h_y) they belong to. Throws std::invalid_argument if the
/// surface has fewer than 2 summits (no σ_s) or E* <= 0.
constitutive::AsperityParameters asperity_parameters(const SummitStatistics& statistics,
                                                     double composite_modulus);

/// Same, from the spectral (Nayak/McCool) estimates (validated: all finite and > 0).
constitutive::AsperityParameters asperity_parameters(const NayakEstimates& estimates,
                                                     double composite_modulus);

/// One row of a resampling study.
struct ResamplingRow
{
  int factor;                  ///< the surface sampled every `factor`-th point
  double sampling_interval;    ///< h·factor [m] (max of the two directions)
  SummitStatistics summits;    ///< counted statistics at this h
  NayakEstimates spectral;     ///< finite-difference Nayak/McCool estimates at this h
};

/// η, β, σ_s (counted and spectral) of `surface` decimated by each factor (1, 2, 4, ...).
/// Factors that leave fewer than 3 x 3 points are rejected (std::invalid_argument).
std::vector<ResamplingRow> resampling_study(const Surface& surface,
                                            const std::vector<int>& factors);

} // namespace rockjoint::topography
