// SPDX-License-Identifier: MIT
#pragma once
/// @file spectral_moments.hpp
/// Spectral moments of an isotropic Gaussian surface and the Nayak (1971) / McCool (1986)
/// summit statistics that follow from them (theory §3), to set beside the counted summits.
///
/// Profile moments: m0 = σ² (height variance), m2 = <(dz/dx)²>, m4 = <(d²z/dx²)²>, averaged
/// over the x and y directions (isotropy assumed; both are reported). Bandwidth α = m0 m4/m2².
///   η = m4 / (6π√3 m2)    β = 0.375 √(π/m4)    σ_s = √(1 - 0.8968/α) σ

#include "power_spectrum.hpp"
#include "surface.hpp"

namespace rockjoint::topography
{

/// Profile spectral moments m0 [m²], m2 [-], m4 [1/m²].
struct SpectralMoments
{
  double m0 = 0.0; ///< m0 = σ² [m²]
  double m2 = 0.0;   ///< (m2x + m2y)/2
  double m4 = 0.0;   ///< (m4x + m4y)/2
  double m2x = 0.0; ///< m2 of profiles along x [-]
  double m2y = 0.0; ///< m2 of profiles along y [-]
  double m4x = 0.0; ///< m4 of profiles along x [1/m²]
  double m4y = 0.0; ///< m4 of profiles along y [1/m²]
  double bandwidth() const { return m0 * m4 / (m2 * m2); } ///< α [-]
};

/// Nayak/McCool summit statistics of an isotropic Gaussian surface.
struct NayakEstimates
{
  double sampling_interval = 0.0; ///< h the moments were computed at [m] (max of h_x, h_y)
  double summit_density = 0.0;    ///< η = m4/(6π√3 m2) [1/m²]
  double summit_radius = 0.0;     ///< β = 0.375 √(π/m4) [m]
  double summit_height_std = 0.0; ///< σ_s = √(1 - 0.8968/α) σ [m] (NaN if α < 0.8968)
  double bandwidth = 0.0;         ///< α [-]
  SpectralMoments moments; ///< the moments the estimates come from
};

/// Moments from finite differences of the samples: forward differences for slopes and the
/// 3-point second difference for curvatures, over every pair/triple of valid points (masks
/// respected). These are the moments the sampled surface actually has at its h.
SpectralMoments finite_difference_moments(const Surface& surface);

/// Moments from the 2D periodogram: m2x = Σ q_x² C Δq², m4x = Σ q_x⁴ C Δq² (likewise y).
/// Complete grids only (see power_spectrum_2d).
SpectralMoments psd_moments(const Surface& surface, Window window = Window::hann);

/// η, β, σ_s from moments (sampling interval recorded for the caller).
NayakEstimates nayak_estimates(const SpectralMoments& moments, double sampling_interval);

} // namespace rockjoint::topography
