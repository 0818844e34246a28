// SPDX-License-Identifier: MIT
#pragma once
/// @file summits.hpp
/// Summits of a sampled surface and their statistics (theory §3): the η, β, σ_s of GW.
///
/// A summit is a valid point strictly higher than all 8 neighbours, all of which must be
/// valid (a point next to the border or to a missing point is not *eligible*: it cannot be
/// tested). Curvature κ = -½∇²s from the 5-point stencil
///   ∇²s ≈ (s_{i,j-1} - 2s_{i,j} + s_{i,j+1})/h_x² + (s_{i-1,j} - 2s_{i,j} + s_{i+1,j})/h_y²,
/// exact for paraboloids; at a strict 8-neighbour summit κ > 0. The summit radius is 1/κ.
/// The scanned area is (eligible points) × h_x h_y, so that for i.i.d. noise η h_x h_y = 1/9.

#include "surface.hpp"

#include <cstdint>
#include <vector>

namespace rockjoint::topography
{

/// The empirical summit list: one entry per summit (feeds the empirical GW law).
struct SummitList
{
  std::vector<std::int32_t> rows;    ///< lattice row i (y) of each summit
  std::vector<std::int32_t> cols;    ///< lattice column j (x)
  std::vector<double> heights;       ///< above the mean plane of the surface [m]
  std::vector<double> curvatures;    ///< κ = -½∇²s > 0 [1/m]
  /// Number of summits.
  std::size_t size() const { return heights.size(); }
  /// Radii 1/κ [m].
  std::vector<double> radii() const;
};

/// GW statistics of the summits, with the sampling interval they belong to (η ~ h⁻², β ~ h^1.1:
/// a parameter set without its h is meaningless).
struct SummitStatistics
{
  double sampling_interval_x = 0.0;  ///< h_x [m]
  double sampling_interval_y = 0.0;  ///< h_y [m]
  std::int64_t summit_count = 0; ///< summits found
  std::int64_t eligible_points = 0;  ///< points whose 8 neighbours are all valid
  double scanned_area = 0.0;         ///< eligible_points · h_x h_y [m²]
  double summit_density = 0.0;       ///< η = summit_count / scanned_area [1/m²]
  double summit_radius = 0.0;        ///< β = 1/mean(κ) [m] (NaN without summits)
  double mean_summit_radius = 0.0;   ///< mean(1/κ) [m], the per-summit alternative
  double mean_curvature = 0.0;       ///< mean(κ) [1/m]
  double summit_height_std = 0.0;    ///< σ_s, sample std (n-1) of summit heights [m]
  double mean_summit_height = 0.0;   ///< mean summit height above the mean plane [m]
  double highest_summit = 0.0;       ///< max summit height above the mean plane [m]
  double surface_rms = 0.0;          ///< σ, rms of the surface heights [m]
};

/// Summits and their statistics.
struct SummitAnalysis
{
  SummitList summits; ///< the summits
  SummitStatistics statistics; ///< their statistics
};

/// Find the 8-neighbour summits of `surface` (heights taken relative to the mean of its
/// valid points) and compute their statistics. Never throws for valid Surfaces; no summit
/// gives η = 0 and NaN β, σ_s.
SummitAnalysis analyse_summits(const Surface& surface);

/// κ = -½∇²s at every point with a complete 5-point stencil, NaN elsewhere [1/m].
HeightGrid curvature_field(const Surface& surface);

} // namespace rockjoint::topography
