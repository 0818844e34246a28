// SPDX-License-Identifier: MIT
#pragma once
/// @file self_affine.hpp
/// Synthetic joint walls: isotropic, Gaussian, self-affine surfaces by Fourier filtering of
/// white noise, and mated pairs of walls (theory §3; Brown 1995 style matedness).
///
/// Power spectrum (isotropic, q = |q| = 2π/λ):
///   C(q) ∝ 1                          for q < q_r = 2π/λ_r   (roll-off plateau)
///   C(q) ∝ (q/q_r)^{-2(1+H)}          for q_r <= q <= q_s = 2π/λ_s
///   C(q) = 0                          for q > q_s           (short-wavelength cut-off)
/// so a profile has the 1D spectrum slope -(1+2H) and the 2D radial spectrum -2(1+H).
/// The q = 0 mode is removed: the mean height is exactly 0.

#include "surface.hpp"

#include <cstdint>
#include <utility>

namespace rockjoint::topography
{

/// What a synthetic wall looks like.
struct SelfAffineSpectrum
{
  double hurst_exponent = 0.8;       ///< H [-], in (0, 1]
  double rms_height = 1e-3;          ///< requested rms height [m], > 0
  double rolloff_wavelength = 0.0;   ///< λ_r [m]; 0 = the longer side of the grid (no plateau)
  double cutoff_wavelength = 0.0;    ///< λ_s [m]; 0 = Nyquist (2 × the larger spacing)
};

/// Grid and randomness of a synthesis.
struct SynthesisGrid
{
  Eigen::Index rows = 256;      ///< points along y
  Eigen::Index cols = 256;      ///< points along x
  double spacing = 0.5e-3;      ///< h [m] (square lattice)
  std::uint64_t seed = 1;       ///< same seed -> bit-identical surface on every run
  /// true: rescale so the realised rms equals rms_height exactly; false: the filter is
  /// normalised so the *expected* variance is rms_height² (the realised rms fluctuates
  /// with the long-wavelength modes).
  bool exact_rms = true;
};

/// The discrete filter shape C(q) (unnormalised, 1 on the plateau) of `spectrum` on `grid`,
/// after defaults are resolved. Exposed for tests and the power-spectrum plot.
double spectrum_shape(const SelfAffineSpectrum& spectrum, double q, double q_rolloff,
                      double q_cutoff);

/// One self-affine Gaussian wall. Throws std::invalid_argument naming the parameter for H
/// outside (0, 1], rms <= 0, cut-off below Nyquist, roll-off below cut-off, grids < 2 x 2.
Surface self_affine_surface(const SelfAffineSpectrum& spectrum, const SynthesisGrid& grid);

/// A mated pair (upper, lower) of walls in one frame. Both share the Fourier components of
/// wavelength >= λ_m (matedness wavelength); below λ_m the lower wall has an independent
/// random component with the same spectrum (the mismatch). λ_m = 0: perfectly mated, the
/// walls are identical. The upper wall equals self_affine_surface() for the same seed; with
/// exact_rms both walls are scaled by the one factor that makes the upper rms exact.
std::pair<Surface, Surface> mated_pair(const SelfAffineSpectrum& spectrum,
                                       const SynthesisGrid& grid, double matedness_wavelength);

} // namespace rockjoint::topography
