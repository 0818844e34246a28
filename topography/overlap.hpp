// SPDX-License-Identifier: MIT
#pragma once
/// @file overlap.hpp
/// Geometric overlap ratio fraction{e <= Δ}: the share of the nominal area where the rigid
/// walls, closed by Δ from first contact, would interpenetrate. A purely geometric contact-area
/// measure for Eq. (2) of Tang & Jiao 2018 (theory §3 [choice]); it ignores elastic
/// deformation, so it over-estimates the elastic GW area (roughly by 2 at small Δ: the
/// Hertz contact radius² is R w, the geometric one 2 R w).

#include "surface.hpp"

#include <span>
#include <vector>

namespace rockjoint::topography
{

/// The distribution of the aperture over the valid lattice points.
class ApertureDistribution
{
public:
  /// Throws std::invalid_argument if the aperture has no valid point.
  explicit ApertureDistribution(const Surface& aperture);

  /// fraction{e <= Δ} [-] for a closure Δ [m]; 0 for Δ < min e, NaN for NaN.
  double overlap_ratio(double closure) const;

  /// Batch version (output size = input size).
  void overlap_ratio(std::span<const double> closure, std::span<double> ratio) const;

  /// Sorted valid apertures [m].
  const std::vector<double>& sorted_apertures() const { return _sorted; }

private:
  std::vector<double> _sorted;
};

} // namespace rockjoint::topography
