#include "half_space.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <fftw3.h>

#include <cstdlib>
#include <thread>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rockjoint::contact
{

namespace validation = rockjoint::constitutive::validation;

namespace
{
/// G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|): the double antiderivative of 1/√(X²+Y²)
/// (∂²G/∂X∂Y = 1/ρ) without the X ln|X| + Y ln|Y| terms, which cancel in the four-corner sum
/// below; written with asinh so that no ln(Y + ρ) loses digits for Y < 0.
double love_primitive(double x, double y)
{
  double g = 0.0;
  if (x != 0.0)
    g += x * std::asinh(y / std::abs(x));
  if (y != 0.0)
    g += y * std::asinh(x / std::abs(y));
  return g;
}
} // namespace

/// FFTW's threads for large transforms: every core of the machine (ROCKJOINT_FFT_THREADS
/// overrides, e.g. 1 under several MPI ranks), from 512² up (below it the threads cost more
/// than they save). Set before each plan; planning happens in constructors only.
void plan_threads(std::size_t size)
{
  static const int available = []
  {
    fftw_init_threads();
    if (const char* env = std::getenv("ROCKJOINT_FFT_THREADS"))
      return std::max(1, std::atoi(env));
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }();
  fftw_plan_with_nthreads(size >= 512 * 512 ? available : 1);
}

struct HalfSpace::Fft
{
  std::size_t m0, m1;     // transform grid (padded for the non-periodic kernel)
  double* real = nullptr; // m0 × m1
  fftw_complex* spectrum = nullptr; // m0 × (m1/2 + 1)
  std::vector<std::complex<double>> kernel; // K̂ / (m0 m1): the normalisation folded in
  fftw_plan forward = nullptr, backward = nullptr;

  Fft(std::size_t rows, std::size_t cols) : m0(rows), m1(cols)
  {
    plan_threads(m0 * m1);
    real = fftw_alloc_real(m0 * m1);
    spectrum = fftw_alloc_complex(m0 * (m1 / 2 + 1));
    if (!real || !spectrum)
      throw std::bad_alloc();
    const int n0 = static_cast<int>(m0), n1 = static_cast<int>(m1);
    forward = fftw_plan_dft_r2c_2d(n0, n1, real, spectrum, FFTW_MEASURE);
    backward = fftw_plan_dft_c2r_2d(n0, n1, spectrum, real, FFTW_MEASURE);
    kernel.resize(m0 * (m1 / 2 + 1));
  }
  ~Fft()
  {
    fftw_destroy_plan(forward);
    fftw_destroy_plan(backward);
    fftw_free(real);
    fftw_free(spectrum);
  }
};

HalfSpace::HalfSpace(std::size_t rows, std::size_t cols, double spacing_x, double spacing_y,
                     double composite_modulus, Kernel kernel)
    : _rows(rows), _cols(cols),
      _hx(validation::positive("HalfSpace", "spacing_x", spacing_x, "m")),
      _hy(validation::positive("HalfSpace", "spacing_y", spacing_y, "m")),
      _modulus(validation::positive("HalfSpace", "composite_modulus", composite_modulus, "Pa")),
      _kernel(kernel)
{
  if (rows < 2 || cols < 2)
    throw std::invalid_argument("HalfSpace: grid " + std::to_string(rows) + " x "
                                + std::to_string(cols) + " is too small (at least 2 x 2)");
  const bool periodic = kernel == Kernel::periodic;
  _fft = std::make_unique<Fft>(periodic ? rows : 2 * rows, periodic ? cols : 2 * cols);
  Fft& f = *_fft;
  const std::size_t half = f.m1 / 2 + 1;
  const double scale = 1.0 / static_cast<double>(f.m0 * f.m1);
  if (periodic)
  {
    // û = 2 p̂/(E*|q|), q = 2π (k_x/L_x, k_y/L_y); q = 0 dropped (mean displacement 0).
    const double lx = _hx * static_cast<double>(cols), ly = _hy * static_cast<double>(rows);
    for (std::size_t i = 0; i < f.m0; ++i)
    {
      const double ki = i <= f.m0 / 2 ? double(i) : double(i) - double(f.m0);
      const double qy = 2.0 * std::numbers::pi * ki / ly;
      for (std::size_t j = 0; j < half; ++j)
      {
        const double qx = 2.0 * std::numbers::pi * double(j) / lx;
        const double q = std::hypot(qx, qy);
        f.kernel[i * half + j] = q > 0.0 ? 2.0 / (_modulus * q) * scale : 0.0;
      }
    }
    // Real-space kernel: the displacement field of a unit nodal pressure at node (0, 0).
    std::copy_n(reinterpret_cast<const double*>(f.kernel.data()), 2 * f.kernel.size(),
                reinterpret_cast<double*>(f.spectrum));
    fftw_execute(f.backward);
    _kernel_real.assign(f.real, f.real + f.m0 * f.m1);
    return;
  }
  // Love's influence coefficients on the wrapped 2n grid (offsets -n..n-1), transformed once.
  for (std::size_t i = 0; i < f.m0; ++i)
  {
    const double dy = (i < rows ? double(i) : double(i) - double(f.m0)) * _hy;
    for (std::size_t j = 0; j < f.m1; ++j)
    {
      const double dx = (j < cols ? double(j) : double(j) - double(f.m1)) * _hx;
      f.real[i * f.m1 + j] = influence(dx, dy);
    }
  }
  _kernel_real.assign(f.real, f.real + f.m0 * f.m1);
  fftw_execute(f.forward);
  for (std::size_t k = 0; k < f.kernel.size(); ++k)
    f.kernel[k] = std::complex<double>(f.spectrum[k][0], f.spectrum[k][1]) * scale;
}

HalfSpace::~HalfSpace() = default;

double HalfSpace::influence(double dx, double dy) const
{
  // Uniform unit pressure on [-a, a] × [-b, b]: u = (1/(π E*)) ∫∫ dA/ρ (Boussinesq), the
  // four-corner sum of the primitive (Love 1929; Johnson 1985, Eq. 3.25).
  const double a = 0.5 * _hx, b = 0.5 * _hy;
  const double sum = love_primitive(dx + a, dy + b) - love_primitive(dx + a, dy - b)
                     - love_primitive(dx - a, dy + b) + love_primitive(dx - a, dy - b);
  return sum / (std::numbers::pi * _modulus);
}

void HalfSpace::displacement_on(std::span<const std::size_t> nodes, std::span<const double> values,
                                std::span<double> out) const
{
  const std::ptrdiff_t m0 = std::ptrdiff_t(_fft->m0), m1 = std::ptrdiff_t(_fft->m1);
  const std::size_t m = nodes.size();
  thread_local std::vector<std::ptrdiff_t> row, col;
  row.resize(m);
  col.resize(m);
  for (std::size_t b = 0; b < m; ++b)
  {
    row[b] = std::ptrdiff_t(nodes[b] / _cols);
    col[b] = std::ptrdiff_t(nodes[b] % _cols);
  }
  const double* kernel = _kernel_real.data();
  for (std::size_t a = 0; a < m; ++a)
  {
    double sum = 0.0;
    for (std::size_t b = 0; b < m; ++b)
    {
      std::ptrdiff_t di = row[a] - row[b], dj = col[a] - col[b]; // wrapped offset
      di += di < 0 ? m0 : 0;
      dj += dj < 0 ? m1 : 0;
      sum += kernel[di * m1 + dj] * values[b];
    }
    out[a] = sum;
  }
}

void HalfSpace::displacement(std::span<const double> pressure, std::span<double> displacement)
{
  const std::size_t n = _rows * _cols;
  if (pressure.size() != n || displacement.size() != n)
    throw std::invalid_argument("HalfSpace::displacement: arrays must have rows*cols = "
                                + std::to_string(n) + " entries (got "
                                + std::to_string(pressure.size()) + " and "
                                + std::to_string(displacement.size()) + ")");
  Fft& f = *_fft;
  // Periodic kernel: the caller's arrays have the transform's layout, so FFTW reads and writes
  // them directly (new-array execute; r2c keeps its input) when they are aligned like the
  // planning buffers; otherwise, and for the zero-padded kernel, through the buffer.
  const bool direct = f.m0 == _rows
                      && fftw_alignment_of(const_cast<double*>(pressure.data()))
                             == fftw_alignment_of(f.real)
                      && fftw_alignment_of(displacement.data()) == fftw_alignment_of(f.real);
  if (direct)
    fftw_execute_dft_r2c(f.forward, const_cast<double*>(pressure.data()), f.spectrum);
  else
  {
    if (f.m0 != _rows)
      std::fill(f.real, f.real + f.m0 * f.m1, 0.0); // zero padding
    for (std::size_t i = 0; i < _rows; ++i)
      std::copy_n(pressure.data() + i * _cols, _cols, f.real + i * f.m1);
    fftw_execute(f.forward);
  }
  // Spectrum × kernel written out: std::complex's operator* checks for NaN (C99 Annex G)
  // at a cost that shows on large grids.
  const std::size_t m = f.kernel.size();
  const double* kernel = reinterpret_cast<const double*>(f.kernel.data());
  for (std::size_t k = 0; k < m; ++k)
  {
    const double a = f.spectrum[k][0], b = f.spectrum[k][1];
    const double c = kernel[2 * k], d = kernel[2 * k + 1];
    f.spectrum[k][0] = a * c - b * d;
    f.spectrum[k][1] = a * d + b * c;
  }
  if (direct)
  {
    fftw_execute_dft_c2r(f.backward, f.spectrum, displacement.data());
    return;
  }
  fftw_execute(f.backward);
  for (std::size_t i = 0; i < _rows; ++i)
    std::copy_n(f.real + i * f.m1, _cols, displacement.data() + i * _cols);
}

} // namespace rockjoint::contact
