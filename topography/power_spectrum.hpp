// SPDX-License-Identifier: MIT
#pragma once
/// @file power_spectrum.hpp
/// Power spectral density of a sampled surface, its radial average and the Hurst exponent
/// fitted to it.
///
/// Normalisation: C(q) [m⁴] on the DFT lattice q = (q_x, q_y) [rad/m] with
/// Σ_k C(q_k) Δq_x Δq_y = mean(z²) (Parseval): C_k = |Z_k|² / (N² Δq_x Δq_y), Δq = 2π/(n h).

#include "surface.hpp"

#include <cstdint>
#include <vector>

namespace rockjoint::topography
{

/// Taper applied before the DFT. A measured (non-periodic) surface needs one: the jump
/// between opposite edges otherwise leaks a q⁻² tail into every moment and slope.
enum class Window : int
{
  none = 0, ///< periodic data (synthetic surfaces)
  hann = 1, ///< separable Hann window, power-normalised (mean w² = 1)
};

/// The 2D periodogram: C on the DFT lattice (row-major, unshifted DFT order) with the
/// frequencies of its rows and columns.
struct PowerSpectrum2D
{
  HeightGrid psd;              ///< C(q_y(i), q_x(j)) [m⁴]
  std::vector<double> qx;      ///< [rad/m], DFT order
  std::vector<double> qy;      ///< [rad/m], DFT order
  double dqx = 0.0; ///< lattice step in q_x [rad/m]
  double dqy = 0.0; ///< lattice step in q_y [rad/m]
};

/// Periodogram of the mean-removed heights. Throws std::invalid_argument if the surface has
/// missing points (a spectrum of a masked grid would need invented values: crop first).
PowerSpectrum2D power_spectrum_2d(const Surface& surface, Window window = Window::hann);

/// Radially averaged spectrum: bins of width max(dq_x, dq_y) up to the smaller Nyquist
/// frequency; empty bins are dropped.
struct RadialSpectrum
{
  std::vector<double> q;          ///< mean |q| of the modes in each bin [rad/m]
  std::vector<double> psd;        ///< mean C in each bin [m⁴]
  std::vector<std::int64_t> count;///< modes in each bin
};

/// The radial average of `spectrum`.
RadialSpectrum radial_average(const PowerSpectrum2D& spectrum);

/// Power-law fit C = C0 (q/q_ref)^{-2(1+H)} over q_min <= q <= q_max.
struct HurstFit
{
  double hurst_exponent;  ///< H = -slope/2 - 1
  double slope;           ///< d ln C / d ln q
  double slope_std_error; ///< from the weighted residuals
  double log_prefactor;   ///< ln C at q = 1 rad/m
  double q_min; ///< lower end of the band used [rad/m]
  double q_max; ///< upper end of the band used [rad/m]
  std::size_t bins;       ///< bins used
};

/// Least-squares fit of ln C against ln q, each bin weighted by its mode count (the
/// periodogram ordinate of one mode is exponentially distributed, so var ln C_bin ≈ 1/count).
/// Throws std::invalid_argument if fewer than 3 bins fall in the band.
HurstFit fit_hurst_exponent(const RadialSpectrum& spectrum, double q_min, double q_max);

} // namespace rockjoint::topography
