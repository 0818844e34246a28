// SPDX-License-Identifier: MIT
#include "self_affine.hpp"

#include "fft2.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace rockjoint::topography
{

namespace validation = rockjoint::constitutive::validation;

namespace
{
/// Standard normal deviates from mt19937_64 by Box-Muller: both are fully specified, so a
/// seed gives the same numbers with every compiler and standard library
/// (std::normal_distribution is implementation-defined).
class NormalStream
{
public:
  explicit NormalStream(std::uint64_t seed) : _engine(seed) {}
  double next()
  {
    if (_has_spare)
    {
      _has_spare = false;
      return _spare;
    }
    const double u1 = uniform_open(), u2 = uniform_open();
    const double r = std::sqrt(-2.0 * std::log(u1)), t = 2.0 * std::numbers::pi * u2;
    _spare = r * std::sin(t);
    _has_spare = true;
    return r * std::cos(t);
  }

private:
  double uniform_open() // in (0, 1)
  {
    return (static_cast<double>(_engine() >> 11) + 0.5) * 0x1.0p-53;
  }
  std::mt19937_64 _engine;
  double _spare = 0.0;
  bool _has_spare = false;
};

ComplexGrid white_noise_spectrum(NormalStream& noise, Eigen::Index rows, Eigen::Index cols)
{
  ComplexGrid w(rows, cols);
  for (Eigen::Index k = 0; k < w.size(); ++k)
    w.data()[k] = noise.next();
  fft2(w);
  return w;
}

struct Filter
{
  HeightGrid amplitude; ///< √C(q) normalised so that E[z²] = rms²
  HeightGrid q;         ///< |q| [rad/m] of each DFT index
};

Filter make_filter(const SelfAffineSpectrum& s, const SynthesisGrid& g)
{
  const char* owner = "self_affine_surface";
  if (!(s.hurst_exponent > 0.0 && s.hurst_exponent <= 1.0))
    validation::fail(owner, "hurst_exponent", s.hurst_exponent, "", "in (0, 1]");
  validation::positive(owner, "rms_height", s.rms_height, "m");
  validation::positive(owner, "spacing", g.spacing, "m");
  if (g.rows < 2 || g.cols < 2)
    validation::fail(owner, g.rows < 2 ? "rows" : "cols",
                     static_cast<double>(std::min(g.rows, g.cols)), "", ">= 2");
  const double nyquist = 2.0 * g.spacing;
  const double cutoff = s.cutoff_wavelength > 0.0 ? s.cutoff_wavelength : nyquist;
  if (cutoff < nyquist * (1.0 - 1e-12))
    validation::fail(owner, "cutoff_wavelength", cutoff, "m",
                     ">= the Nyquist wavelength 2h = " + std::to_string(nyquist) + " m");
  const double size = static_cast<double>(std::max(g.rows, g.cols)) * g.spacing;
  const double rolloff = s.rolloff_wavelength > 0.0 ? s.rolloff_wavelength : size;
  validation::non_negative(owner, "rolloff_wavelength", s.rolloff_wavelength, "m");
  if (rolloff < cutoff)
    validation::fail(owner, "rolloff_wavelength", rolloff, "m",
                     ">= cutoff_wavelength = " + std::to_string(cutoff) + " m");
  const double q_r = 2.0 * std::numbers::pi / rolloff, q_s = 2.0 * std::numbers::pi / cutoff;

  Filter f{HeightGrid(g.rows, g.cols), HeightGrid(g.rows, g.cols)};
  double sum = 0.0;
  for (Eigen::Index i = 0; i < g.rows; ++i)
  {
    const double qy = angular_frequency(i, g.rows, g.spacing);
    for (Eigen::Index j = 0; j < g.cols; ++j)
    {
      const double qx = angular_frequency(j, g.cols, g.spacing);
      const double q = std::hypot(qx, qy);
      const double c = spectrum_shape(s, q, q_r, q_s);
      f.q(i, j) = q;
      f.amplitude(i, j) = c;
      sum += c;
    }
  }
  if (!(sum > 0.0))
    throw std::invalid_argument("self_affine_surface: no Fourier mode of the grid lies in the "
                                "requested band; enlarge the grid or widen the wavelengths");
  // z = IDFT(F W) with E|W_k|² = N gives E[z²] = Σ F_k² / N: choose F² = C · rms² N / Σ C.
  const double n = static_cast<double>(g.rows * g.cols);
  f.amplitude = (f.amplitude * (s.rms_height * s.rms_height * n / sum)).sqrt();
  return f;
}

HeightGrid real_part_of_inverse(ComplexGrid spectrum)
{
  fft2(spectrum, true);
  return spectrum.real();
}
} // namespace

double spectrum_shape(const SelfAffineSpectrum& spectrum, double q, double q_rolloff,
                      double q_cutoff)
{
  if (q <= 0.0 || q > q_cutoff * (1.0 + 1e-12))
    return 0.0;
  if (q < q_rolloff)
    return 1.0;
  return std::pow(q / q_rolloff, -2.0 * (1.0 + spectrum.hurst_exponent));
}

Surface self_affine_surface(const SelfAffineSpectrum& spectrum, const SynthesisGrid& grid)
{
  return mated_pair(spectrum, grid, 0.0).first;
}

std::pair<Surface, Surface> mated_pair(const SelfAffineSpectrum& spectrum,
                                       const SynthesisGrid& grid, double matedness_wavelength)
{
  validation::non_negative("mated_pair", "matedness_wavelength", matedness_wavelength, "m");
  const Filter f = make_filter(spectrum, grid);
  NormalStream noise(grid.seed);
  const ComplexGrid upper_noise = white_noise_spectrum(noise, grid.rows, grid.cols);
  HeightGrid upper = real_part_of_inverse(upper_noise * f.amplitude.cast<std::complex<double>>());
  HeightGrid lower = upper;
  if (matedness_wavelength > 0.0)
  {
    // The second wall continues the same random stream: deterministic for the seed.
    const ComplexGrid lower_noise = white_noise_spectrum(noise, grid.rows, grid.cols);
    const double q_m = 2.0 * std::numbers::pi / matedness_wavelength;
    ComplexGrid mixed = upper_noise;
    for (Eigen::Index k = 0; k < mixed.size(); ++k)
      if (f.q.data()[k] > q_m) // wavelengths shorter than λ_m: independent mismatch
        mixed.data()[k] = lower_noise.data()[k];
    lower = real_part_of_inverse(mixed * f.amplitude.cast<std::complex<double>>());
  }
  if (grid.exact_rms)
  {
    const double realised = std::sqrt(upper.square().mean());
    const double scale = spectrum.rms_height / realised;
    upper *= scale;
    lower *= scale;
  }
  return {Surface(std::move(upper), grid.spacing), Surface(std::move(lower), grid.spacing)};
}

} // namespace rockjoint::topography
