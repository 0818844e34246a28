// SPDX-License-Identifier: MIT
#pragma once
/// @file half_space.hpp
/// Surface displacement of an elastic half-space under a pressure field on a regular grid:
/// the influence operator u = K p of the boundary-element contact reference
/// (docs/contact.md). Lengths in m, pressures in Pa, modulus E* in Pa (composite: the
/// contact of two elastic walls is that of a rigid surface carrying the composite topography
/// with a half-space of modulus E*, theory §1).
///
/// Periodic (synthetic periodic surfaces): û(q) = 2 p̂(q)/(E*|q|) for q ≠ 0 and û(0) = 0, i.e.
/// mean(u) = 0: the uniform-pressure (bulk) deformation is removed exactly.
/// Non-periodic (real scans): each node carries a uniform pressure on its h_x × h_y cell
/// whose displacement is Love's closed form (Johnson 1985, §3.2); the discrete convolution is
/// applied by FFT on a zero-padded 2n_y × 2n_x grid (DC-FFT, Liu et al. 2000), so no image
/// of the patch loads it. The mean displacement then contains the bulk compliance of the
/// patch, which the contact solver removes when it reports closure.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace rockjoint::contact
{

/// Which half-space the grid sits on.
enum class Kernel : int
{
  periodic = 0,     ///< the grid is one period of an infinite periodic surface
  non_periodic = 1, ///< the grid is an isolated patch of an infinite half-space
};

/// The influence operator u = K p [m] of an elastic half-space of modulus E* [Pa] under a
/// pressure p [Pa] on a regular grid, periodic or not (file comment: the kernels).
class HalfSpace
{
public:
  /// @param rows, cols grid size (row-major like numpy; x along a row)
  /// @param spacing_x, spacing_y lattice steps [m], > 0
  /// @param composite_modulus E* [Pa], > 0
  /// @param kernel periodic or non-periodic half-space
  /// Throws std::invalid_argument naming a bad argument.
  HalfSpace(std::size_t rows, std::size_t cols, double spacing_x, double spacing_y,
            double composite_modulus, Kernel kernel);
  ~HalfSpace();
  HalfSpace(const HalfSpace&) = delete;
  HalfSpace& operator=(const HalfSpace&) = delete;

  /// u = K p: surface displacement [m] (positive away from the other wall) under the nodal
  /// pressures `pressure` [Pa] (rows·cols, row-major). Not thread-safe (shared FFT buffers).
  void displacement(std::span<const double> pressure, std::span<double> displacement);

  /// Displacement [m] at offset (dx, dy) from the centre of a cell carrying unit pressure:
  /// the non-periodic influence coefficient (Love's closed form).
  double influence(double dx, double dy) const;

  /// u = K p restricted to a node set: out[a] = Σ_b K(node_a - node_b) values[b], by direct
  /// summation over the real-space kernel (|nodes|² operations): cheaper than the FFT while the
  /// set is small (a contact set of a few per cent at most). Same K as displacement().
  /// Summed pair of rows by pair of rows (nodes sorted), so that each offset is read from one
  /// kernel row held in the core's cache, on the transforms' threads.
  void displacement_on(std::span<const std::size_t> nodes, std::span<const double> values,
                       std::span<double> out) const;

  /// displacement ← scale · (displacement - step · response) + K c for a sparse load c (values
  /// at nodes) on the whole grid: K c by direct summation (|nodes| · rows·cols operations, two
  /// contiguous kernel segments per row), cheaper than a transform for a few dozen nodes. One
  /// pass over the grid, row by row (the row stays in the cache while every node adds to it).
  /// Same K as displacement().
  void carry_displacement(double scale, double step, std::span<const double> response,
                          std::span<const std::size_t> nodes, std::span<const double> values,
                          std::span<double> displacement) const;

  /// Points of the transform grid (rows·cols periodic, 4·rows·cols zero-padded).
  std::size_t transform_size() const;
  /// Wall time FFTW's planning of this operator's transforms took [s] (FFTW_MEASURE times
  /// candidate algorithms: seconds at 1024² on the first plan of a size in a process, then
  /// milliseconds, FFTW remembering what it measured; detail::measure_plans).
  double planning_seconds() const;

  /// Grid rows.
  std::size_t rows() const { return _rows; }
  /// Grid columns.
  std::size_t cols() const { return _cols; }
  /// Periodic or non-periodic.
  Kernel kernel() const { return _kernel; }
  /// E* [Pa].
  double composite_modulus() const { return _modulus; }

private:
  struct Fft; // FFTW plans and buffers (kept out of the header)
  std::vector<double> _kernel_real; // K at every wrapped offset of the transform grid
  std::size_t _rows, _cols;
  double _hx, _hy, _modulus;
  Kernel _kernel;
  std::unique_ptr<Fft> _fft;
};

namespace detail
{
/// Transforms of at least this many points are planned with FFTW_MEASURE from their first use.
inline constexpr std::size_t measure_from_points = 1024 * 1024;
/// Smaller ones from their (measure_after_plans + 1)-th plan in a process.
inline constexpr std::size_t measure_after_plans = 8;

/// FFTW's planning effort for a transform of `points` points, the size planned `plans_before`
/// times before in this process: FFTW_MEASURE (true) times candidate algorithms, FFTW_ESTIMATE
/// (false) plans at once from heuristics. Below 1024² points MEASURE's planning costs what its
/// faster transforms save over 6 to 58 closure curves of 15 loads (128²: never), and a scene run
/// solves one curve per size: a fresh process's 256² curve took 0.15 s estimated against 0.43 s
/// measured. So a size is estimated until it has been planned `measure_after_plans` times, then
/// measured (a rent-or-buy rule: never more than about twice the cost of the better choice made
/// in hindsight). From 1024² points MEASURE pays at once (ESTIMATE's transforms 17-41 % slower
/// there). bench/bench_fft_planning.py → bench/results/fft_planning.md; docs/contact.md, "Cost".
bool measure_plans(std::size_t points, std::size_t plans_before);
} // namespace detail

} // namespace rockjoint::contact
