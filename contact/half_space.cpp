// SPDX-License-Identifier: MIT
#include "half_space.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <fftw3.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <mutex>
#include <map>
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

namespace detail
{
bool measure_plans(std::size_t points, std::size_t plans_before)
{
  return plans_before >= measure_after_plans || points >= measure_from_points;
}
} // namespace detail

namespace
{
/// Worker threads for large transforms: every core of the machine (ROCKJOINT_FFT_THREADS
/// overrides, e.g. 1 under several MPI ranks), from 512² up (below it the threads cost more
/// than they save).
int worker_threads(std::size_t size)
{
  static const int available = []
  {
    fftw_init_threads();
    if (const char* env = std::getenv("ROCKJOINT_FFT_THREADS"))
      return std::max(1, std::atoi(env));
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }();
  return size >= 512 * 512 ? available : 1;
}

/// FFTW's planning flag for the transforms of an m0 × m1 grid with `rows` data rows; counts the
/// plans of each size made in this process (a mutex guards the count).
unsigned planning_flag(std::size_t rows, std::size_t m0, std::size_t m1)
{
  static std::mutex mutex;
  static std::map<std::array<std::size_t, 3>, std::size_t> plans; // size -> plans made so far
  const std::lock_guard<std::mutex> lock(mutex);
  const std::size_t before = plans[{rows, m0, m1}]++;
  // ROCKJOINT_FFT_PLANNING=measure|estimate overrides the rule (bench/bench_fft_planning.py)
  static const std::string forced = []
  {
    const char* env = std::getenv("ROCKJOINT_FFT_PLANNING");
    const std::string value = env ? env : "auto";
    if (value != "auto" && value != "measure" && value != "estimate")
      throw std::invalid_argument("ROCKJOINT_FFT_PLANNING must be auto, measure or estimate, got '"
                                  + value + "'");
    return value;
  }();
  if (forced != "auto")
    return forced == "measure" ? FFTW_MEASURE : FFTW_ESTIMATE;
  return detail::measure_plans(m0 * m1, before) ? FFTW_MEASURE : FFTW_ESTIMATE;
}

/// Calls work(begin, end, worker) on `workers` contiguous slices of [0, count), the first on
/// the calling thread. Spawning costs tens of µs, a fraction of a per cent of a large transform.
template <class Work>
void in_parallel(std::size_t count, int workers, const Work& work)
{
  const std::size_t w = std::min<std::size_t>(std::size_t(std::max(workers, 1)), std::max<std::size_t>(count, 1));
  std::vector<std::thread> others;
  for (std::size_t t = 1; t < w; ++t)
    others.emplace_back([&, t] { work(t * count / w, (t + 1) * count / w, int(t)); });
  work(0, count / w, 0);
  for (std::thread& t : others)
    t.join();
}


/// Columns per block of the fused column pass of the zero-padded transform (forward FFT,
/// × kernel, backward FFT on a block that stays in the core's cache): 32 was the fastest of
/// 4, 8, 16, 32 at 1024² (16.0 against 17.5-22.7 ms per transform pair on two threads;
/// docs/contact.md, "Cost").
constexpr std::size_t column_block = 32;
} // namespace

struct HalfSpace::Fft
{
  std::size_t m0, m1;     // transform grid (padded for the non-periodic kernel)
  std::size_t half;       // m1/2 + 1 complex columns of the r2c spectrum
  std::size_t rows;       // rows that carry data (m0 periodic, m0/2 padded)
  int workers;            // threads of the transforms and of the passes around them
  double* real = nullptr; // m0 × m1
  fftw_complex* spectrum = nullptr; // m0 × half (padded: only the `rows` data rows are used)
  /// K̂ / (m0 m1), the normalisation folded in: real, as K is even (K(-x) = K(x) on the
  /// wrapped grid). Periodic: row major m0 × half; padded: column major half × m0 (the layout
  /// of the column blocks).
  std::vector<double> kernel;
  // Periodic: the 2D plans. Padded: the pruned DC-FFT. Forward r2c of the `rows` data rows
  // only (the other rows are zero); then, per block of columns copied out to a contiguous
  // buffer (padded rows zero), the forward column FFT, × K̂ and the backward column FFT, and
  // only the `rows` wanted rows copied back; then c2r of those rows. Half the row transforms
  // are saved, and the columns never leave the cache between the two transforms.
  fftw_plan forward = nullptr, backward = nullptr;          // periodic
  fftw_plan rows_forward = nullptr, rows_backward = nullptr; // padded
  fftw_plan block_forward = nullptr, block_backward = nullptr; // column_block columns
  fftw_plan tail_forward = nullptr, tail_backward = nullptr;   // the last half % column_block
  std::vector<fftw_complex*> buffers;                        // one column block per worker
  double planning_seconds = 0.0;                             // wall time of the planning

  Fft(std::size_t data_rows, std::size_t m0_, std::size_t m1_)
      : m0(m0_), m1(m1_), half(m1_ / 2 + 1), rows(data_rows), workers(worker_threads(m0_ * m1_))
  {
    fftw_plan_with_nthreads(workers);
    real = fftw_alloc_real(m0 * m1);
    spectrum = fftw_alloc_complex(m0 * half);
    if (!real || !spectrum)
      throw std::bad_alloc();
    const int n0 = static_cast<int>(m0), n1 = static_cast<int>(m1);
    const int nh = static_cast<int>(half), nrows = static_cast<int>(rows);
    const unsigned flag = planning_flag(rows, m0, m1);
    const auto planning_start = std::chrono::steady_clock::now();
    bool planned = true;
    if (rows == m0)
    {
      forward = fftw_plan_dft_r2c_2d(n0, n1, real, spectrum, flag);
      backward = fftw_plan_dft_c2r_2d(n0, n1, spectrum, real, flag);
      planned = forward && backward;
    }
    else
    {
      rows_forward = fftw_plan_many_dft_r2c(1, &n1, nrows, real, nullptr, 1, n1, spectrum,
                                            nullptr, 1, nh, flag);
      rows_backward = fftw_plan_many_dft_c2r(1, &n1, nrows, spectrum, nullptr, 1, nh, real,
                                             nullptr, 1, n1, flag);
      fftw_plan_with_nthreads(1); // one block per worker
      for (int t = 0; t < workers; ++t)
        buffers.push_back(fftw_alloc_complex(column_block * m0));
      if (std::find(buffers.begin(), buffers.end(), nullptr) != buffers.end())
        throw std::bad_alloc();
      auto plan_columns = [&](std::size_t count, int sign)
      {
        const int howmany = static_cast<int>(count);
        return fftw_plan_many_dft(1, &n0, howmany, buffers[0], nullptr, 1, n0, buffers[0],
                                  nullptr, 1, n0, sign, flag);
      };
      block_forward = plan_columns(column_block, FFTW_FORWARD);
      block_backward = plan_columns(column_block, FFTW_BACKWARD);
      planned = rows_forward && rows_backward && block_forward && block_backward;
      if (half % column_block != 0)
      {
        tail_forward = plan_columns(half % column_block, FFTW_FORWARD);
        tail_backward = plan_columns(half % column_block, FFTW_BACKWARD);
        planned = planned && tail_forward && tail_backward;
      }
    }
    if (!planned)
      throw std::runtime_error("HalfSpace: FFTW could not plan the " + std::to_string(m0) + " x "
                               + std::to_string(m1) + " transforms");
    planning_seconds
        = std::chrono::duration<double>(std::chrono::steady_clock::now() - planning_start).count();
    kernel.resize(m0 * half);
  }
  ~Fft()
  {
    for (fftw_plan plan : {forward, backward, rows_forward, rows_backward, block_forward,
                           block_backward, tail_forward, tail_backward})
      if (plan)
        fftw_destroy_plan(plan);
    for (fftw_complex* b : buffers)
      fftw_free(b);
    fftw_free(real);
    fftw_free(spectrum);
  }

  /// real = IFFT(K̂ · FFT(real)) (normalised by the kernel), reading only the first `rows`
  /// rows of `real` and writing only those (padded: their padded columns must be zero).
  void convolve()
  {
    if (forward)
    {
      fftw_execute(forward);
      multiply_spectrum();
      fftw_execute(backward);
      return;
    }
    fftw_execute(rows_forward);
    const std::size_t blocks = (half + column_block - 1) / column_block;
    in_parallel(blocks, workers, [&](std::size_t begin, std::size_t end, int worker)
                {
                  for (std::size_t b = begin; b < end; ++b)
                    convolve_columns(b * column_block, std::min(column_block, half - b * column_block),
                                     buffers[std::size_t(worker)]);
                });
    fftw_execute(rows_backward);
  }

  /// Periodic: spectrum ×= K̂ (real).
  void multiply_spectrum()
  {
    for (std::size_t k = 0; k < m0 * half; ++k)
    {
      spectrum[k][0] *= kernel[k];
      spectrum[k][1] *= kernel[k];
    }
  }

  /// Padded: columns [c0, c0 + width) through the column transforms and the kernel.
  void convolve_columns(std::size_t c0, std::size_t width, fftw_complex* buffer)
  {
    for (std::size_t r = 0; r < rows; ++r)
    {
      const fftw_complex* row = spectrum + r * half + c0;
      for (std::size_t c = 0; c < width; ++c)
      {
        buffer[c * m0 + r][0] = row[c][0];
        buffer[c * m0 + r][1] = row[c][1];
      }
    }
    for (std::size_t c = 0; c < width; ++c)
      std::fill(&buffer[c * m0 + rows][0], &buffer[(c + 1) * m0][0], 0.0);
    const bool full = width == column_block;
    fftw_execute_dft(full ? block_forward : tail_forward, buffer, buffer);
    for (std::size_t c = 0; c < width; ++c)
    {
      fftw_complex* column = buffer + c * m0;
      const double* k = kernel.data() + (c0 + c) * m0;
      for (std::size_t r = 0; r < m0; ++r)
      {
        column[r][0] *= k[r];
        column[r][1] *= k[r];
      }
    }
    fftw_execute_dft(full ? block_backward : tail_backward, buffer, buffer);
    for (std::size_t r = 0; r < rows; ++r)
    {
      fftw_complex* row = spectrum + r * half + c0;
      for (std::size_t c = 0; c < width; ++c)
      {
        row[c][0] = buffer[c * m0 + r][0];
        row[c][1] = buffer[c * m0 + r][1];
      }
    }
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
  _fft = std::make_unique<Fft>(rows, periodic ? rows : 2 * rows, periodic ? cols : 2 * cols);
  Fft& f = *_fft;
  const std::size_t half = f.half;
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
    for (std::size_t k = 0; k < f.kernel.size(); ++k)
    {
      f.spectrum[k][0] = f.kernel[k];
      f.spectrum[k][1] = 0.0;
    }
    fftw_execute(f.backward);
    _kernel_real.assign(f.real, f.real + f.m0 * f.m1);
    return;
  }
  // Love's influence coefficients on the wrapped 2n grid (offsets -n..n-1). K is even in both
  // offsets, so one quadrant is evaluated and mirrored: the wrapped kernel is then exactly
  // even, its spectrum real.
  const std::size_t q0 = f.m0 / 2 + 1, q1 = f.m1 / 2 + 1;
  std::vector<double> quadrant(q0 * q1);
  for (std::size_t i = 0; i < q0; ++i)
    for (std::size_t j = 0; j < q1; ++j)
      quadrant[i * q1 + j] = influence(double(j) * _hx, double(i) * _hy);
  for (std::size_t i = 0; i < f.m0; ++i)
  {
    const std::size_t di = std::min(i, f.m0 - i);
    for (std::size_t j = 0; j < f.m1; ++j)
      f.real[i * f.m1 + j] = quadrant[di * q1 + std::min(j, f.m1 - j)];
  }
  _kernel_real.assign(f.real, f.real + f.m0 * f.m1);
  // The kernel fills the whole padded grid: one full 2D transform, planned for this call only.
  fftw_plan whole = fftw_plan_dft_r2c_2d(int(f.m0), int(f.m1), f.real, f.spectrum, FFTW_ESTIMATE);
  if (!whole)
    throw std::runtime_error("HalfSpace: FFTW could not plan the kernel's transform");
  fftw_execute(whole);
  fftw_destroy_plan(whole);
  // Stored column major (the layout of the column blocks); the imaginary part is round-off.
  for (std::size_t i = 0; i < f.m0; ++i)
    for (std::size_t j = 0; j < half; ++j)
      f.kernel[j * f.m0 + i] = f.spectrum[i * half + j][0] * scale;
}

HalfSpace::~HalfSpace() = default;

std::size_t HalfSpace::transform_size() const { return _fft->m0 * _fft->m1; }

double HalfSpace::planning_seconds() const { return _fft->planning_seconds; }

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
  // The nodes in grid order, grouped by row: for a pair of rows (ra, rb) every offset
  // K(ra - rb, ca - cb) lies in one kernel row of m1 values, which stays in the cache while the
  // pair is summed. Taken in the caller's order, consecutive reads jumped across the whole
  // kernel (8 MB periodic, 32 MB zero-padded at 1024²), and those misses were the cost: on the
  // 1024² bench joint the direct sums took longer than the transform they replace.
  const std::ptrdiff_t m0 = std::ptrdiff_t(_fft->m0), m1 = std::ptrdiff_t(_fft->m1);
  const std::size_t m = nodes.size();
  thread_local std::vector<std::size_t> order, group_start;
  thread_local std::vector<std::ptrdiff_t> row, col;
  thread_local std::vector<double> value;
  order.resize(m);
  for (std::size_t a = 0; a < m; ++a)
    order[a] = a;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return nodes[a] < nodes[b]; });
  row.resize(m);
  col.resize(m);
  value.resize(m);
  group_start.clear();
  for (std::size_t s = 0; s < m; ++s)
  {
    row[s] = std::ptrdiff_t(nodes[order[s]] / _cols);
    col[s] = std::ptrdiff_t(nodes[order[s]] % _cols);
    value[s] = values[order[s]];
    if (s == 0 || row[s] != row[s - 1])
      group_start.push_back(s);
  }
  group_start.push_back(m);
  const std::size_t groups = group_start.size() - 1;
  const double* kernel = _kernel_real.data();
  const std::ptrdiff_t* rows = row.data();
  const std::ptrdiff_t* cols = col.data();
  const double* v = value.data();
  const std::size_t* starts = group_start.data();
  const std::size_t* sorted = order.data(); // thread_local: the workers must not name it
  in_parallel(m, _fft->workers, [&](std::size_t begin, std::size_t end, int)
              {
                for (std::size_t s = begin; s < end; ++s)
                {
                  double sum = 0.0;
                  for (std::size_t g = 0; g < groups; ++g)
                  {
                    std::ptrdiff_t di = rows[s] - rows[starts[g]]; // wrapped row offset
                    di += di < 0 ? m0 : 0;
                    const double* krow = kernel + di * m1;
                    for (std::size_t b = starts[g]; b < starts[g + 1]; ++b)
                    {
                      std::ptrdiff_t dj = cols[s] - cols[b];
                      dj += dj < 0 ? m1 : 0;
                      sum += krow[dj] * v[b];
                    }
                  }
                  out[sorted[s]] = sum;
                }
              });
}

void HalfSpace::carry_displacement(double scale, double step, std::span<const double> response,
                                   std::span<const std::size_t> nodes,
                                   std::span<const double> values,
                                   std::span<double> displacement) const
{
  const std::size_t m0 = _fft->m0, m1 = _fft->m1;
  const double* kernel = _kernel_real.data();
  // Serial, like the solver's scan: on the shared bench machine two threads lost more waiting
  // for a core than they gained on a pass of a few ms.
  for (std::size_t i = 0; i < _rows; ++i)
  {
    double* u = displacement.data() + i * _cols;
    const double* r = response.data() + i * _cols;
    for (std::size_t j = 0; j < _cols; ++j)
      u[j] = scale * (u[j] - step * r[j]);
    for (std::size_t b = 0; b < nodes.size(); ++b)
    {
      const std::size_t ib = nodes[b] / _cols, jb = nodes[b] % _cols;
      const double c = values[b];
      // Row offset i - ib wrapped onto the transform grid; columns j < jb read the kernel's
      // wrapped tail m1 - (jb - j), columns j >= jb its head j - jb.
      const double* row = kernel + (i >= ib ? i - ib : i + m0 - ib) * m1;
      const double* tail = row + (m1 - jb);
      for (std::size_t j = 0; j < jb; ++j)
        u[j] += c * tail[j];
      double* right = u + jb;
      for (std::size_t k = 0; k < _cols - jb; ++k)
        right[k] += c * row[k];
    }
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
  {
    fftw_execute_dft_r2c(f.forward, const_cast<double*>(pressure.data()), f.spectrum);
    f.multiply_spectrum();
    fftw_execute_dft_c2r(f.backward, f.spectrum, displacement.data());
    return;
  }
  // Data rows in, their padded columns zeroed (the padded rows are never read), and out.
  in_parallel(_rows, f.workers, [&](std::size_t begin, std::size_t end, int)
              {
                for (std::size_t i = begin; i < end; ++i)
                {
                  std::copy_n(pressure.data() + i * _cols, _cols, f.real + i * f.m1);
                  std::fill(f.real + i * f.m1 + _cols, f.real + (i + 1) * f.m1, 0.0);
                }
              });
  f.convolve();
  in_parallel(_rows, f.workers, [&](std::size_t begin, std::size_t end, int)
              {
                for (std::size_t i = begin; i < end; ++i)
                  std::copy_n(f.real + i * f.m1, _cols, displacement.data() + i * _cols);
              });
}

} // namespace rockjoint::contact
