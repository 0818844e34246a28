// SPDX-License-Identifier: MIT
#pragma once
/// @file reynolds_flow.hpp
/// Steady laminar flow through a joint's aperture field: the Reynolds (local cubic law)
/// equation ∇·(k ∇p) = 0, k = e³/12, on the grid of a mechanical aperture e(x) >= 0 (the gap
/// field of the contact solution under load, contact/elastic_contact.hpp), and the joint's
/// effective transmissivity tensor and hydraulic aperture (docs/flow.md).
///
/// Convention: the mean flux per unit width over the grid's rectangle (masked and closed points
/// included, carrying nothing) is q̄ = -(T/μ) ∇p̄, so T [m³] is "mean flux per unit width per
/// unit pressure gradient times μ"; two parallel plates at spacing e give T = e³/12, and the
/// hydraulic aperture is e_h = (12 T)^(1/3). Column a of T is the mean flux under the unit
/// gradient ∇p̄ = -e_a.
///
/// Discretisation: finite volumes on the grid cells (one cell per grid point, h_x by h_y).
/// A face conducts with the harmonic mean 2 k_i k_j/(k_i + k_j) of its two cells: the exact
/// conductance of the two half cells in series, so that a 1D chain of cells is exact for any
/// aperture profile, a closed cell (e = 0, a contact spot) or a masked one (NaN, not scanned)
/// closes all its faces, and the flux stays continuous across a jump of k (where an arithmetic
/// mean would let flow leak through a closed cell). Conservative by construction: the flux
/// through every cross-section of the grid is the same.
///
/// Boundary conditions, for each of the two imposed gradients:
/// * periodic (a synthetic joint, one period of the periodic BEM kernel): p = ∇p̄·x + φ with φ
///   periodic; one cell per region is pinned (φ = 0), since φ is defined up to a constant;
/// * sealed sides (an isolated scan, the zero-padded BEM kernel): fixed pressures on the two
///   faces normal to the gradient (a drop of L_a across the length L_a: unit gradient),
///   through the half cell next to them; no flow across the two sides parallel to it.
/// Regions of open cells that cannot carry a mean flow (connectivity.hpp) are left out.
///
/// Closed cells: e = 0 (a contact spot: the contact solvers give exactly 0 on their contact set,
/// contact/contact_set.hpp), NaN, and open cells whose k is below 1e-12 of the largest cell's
/// (e < 1e-4 e_max), which the double-precision system cannot resolve (reynolds_flow.cpp). They
/// are removed from the system, not given a tiny conductance. A transmissivity that comes out
/// non-finite or with a negative diagonal term is an error (std::runtime_error), never a result.
///
/// Linear solver (docs/flow.md, bench/results/flow.md): the matrix is the 5-point
/// finite-volume Laplacian, symmetric positive definite once the floating regions are left out
/// or pinned. It is stored on the whole grid, a cell outside the system as an identity row, so
/// that one symbolic analysis serves every system of a grid (both gradients, sealed sides). The
/// default is CHOLMOD's supernodal Cholesky (one factorisation for both gradients of a periodic
/// grid): on the 512² bench joint it is several times faster than Eigen's simplicial LDLᵀ, and
/// incomplete-Cholesky CG needs over a thousand iterations per gradient there
/// (bench/results/flow.md).

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>

namespace rockjoint::flow
{

/// How the grid's edges are treated (see file comment).
enum class Boundary
{
  periodic,
  sealed_sides
};

/// The linear solver of the pressure system.
enum class LinearSolver
{
  cholesky,            ///< sparse Cholesky: CHOLMOD's supernodal one through Eigen (its ordering);
                       ///< built with ROCKJOINT_CHOLMOD=OFF, Eigen's simplicial LLᵀ
  simplicial_cholesky, ///< sparse LDLᵀ (Eigen SimplicialLDLT, AMD ordering)
  conjugate_gradient   ///< CG preconditioned by incomplete Cholesky (Eigen, AMD ordering)
};

/// Options of a ReynoldsFlow solve: the linear solver and its tolerances.
struct FlowOptions
{
  LinearSolver solver = LinearSolver::cholesky; ///< solver of the pressure system
  /// CG: stop at |r| <= tolerance |b| (relative residual of the pressure system)
  double tolerance = 1e-10;
  int maximum_iterations = 10000; ///< CG
};

/// Transmissivity of one aperture field.
struct FlowResult
{
  /// T [m³], row-major (xx, xy, yx, yy): q̄ = -(T/μ) ∇p̄ (see file comment). Periodic: symmetric
  /// to the solver's tolerance. Sealed sides: the off-diagonal terms are the mean transverse
  /// flux inside the grid, biased by the sealed sides and not symmetric in general.
  std::array<double, 4> transmissivity{};
  double mechanical_aperture = 0.0; ///< mean of e over the scanned points, contact spots as 0 [m]
  /// fraction of the scanned points with e > 0 [-] (a contact solution's gap: 1 - A/A0)
  double open_fraction = 0.0;
  /// a path of open (resolved) cells carries flow along x, y (sealed sides: inlet to outlet;
  /// periodic: winding); T_xx > 0 exactly when percolates[0], T_yy likewise
  std::array<bool, 2> percolates{};
  std::array<int, 2> iterations{}; ///< CG iterations under each gradient (0: direct solver)
  /// largest |A p - b| / |b| of the pressure systems solved (0 if none was solved)
  double relative_residual = 0.0;
  bool converged = true; ///< every system met the tolerance (a direct solve: its factorisation)
  /// conjugate_gradient only: CG did not reach the tolerance (near percolation, conductances
  /// spanning many decades) and the supernodal factorisation solved the system instead;
  /// `iterations` are CG's before it gave up
  bool direct_fallback = false;
  std::size_t unknowns = 0; ///< pressure unknowns of the (largest) system
};

namespace detail
{
class PressureSolver;
}

/// The flow problem of one grid (size, spacings, edges, solver). Its pressure systems share one
/// sparsity pattern, whose symbolic factorisation is made once and serves every aperture field
/// given to it (the loads of a closure curve).
class ReynoldsFlow
{
public:
  /// A grid of rows x cols cells of h_x by h_y [m] (x along a row). Throws std::invalid_argument
  /// for fewer than 2 rows or columns, a spacing that is not finite and > 0, or CG options out
  /// of range.
  ReynoldsFlow(std::size_t rows, std::size_t cols, double spacing_x, double spacing_y,
               Boundary boundary, const FlowOptions& options = {});
  ~ReynoldsFlow();
  /// Movable (the factorisation moves with it), not copyable.
  ReynoldsFlow(ReynoldsFlow&&) noexcept;
  /// Move assignment.
  ReynoldsFlow& operator=(ReynoldsFlow&&) noexcept;

  /// Transmissivity of the aperture field `aperture` [m] (rows x cols, row-major like numpy:
  /// entry (i, j) at x = j h_x, y = i h_y; NaN = masked, not scanned, impermeable; 0 = closed).
  /// Throws std::invalid_argument, naming the problem, for a size that is not rows x cols, a
  /// negative or infinite aperture (its row, column and value) or no scanned point;
  /// std::runtime_error for a T that is not finite or has a negative diagonal term.
  FlowResult transmissivity(std::span<const double> aperture);

  /// Grid rows.
  std::size_t rows() const { return _rows; }
  /// Grid columns.
  std::size_t cols() const { return _cols; }

private:
  std::size_t _rows, _cols;
  double _hx, _hy;
  Boundary _boundary;
  FlowOptions _options;
  std::unique_ptr<detail::PressureSolver> _solver;
};

/// One field: ReynoldsFlow(rows, cols, h_x, h_y, boundary, options).transmissivity(aperture)
/// (the errors of both).
FlowResult transmissivity(std::span<const double> aperture, std::size_t rows, std::size_t cols,
                          double spacing_x, double spacing_y, Boundary boundary,
                          const FlowOptions& options = {});

/// Hydraulic aperture e_h = (12 T)^(1/3) [m] of a transmissivity T [m³] (parallel plates: e).
inline double hydraulic_aperture(double transmissivity)
{
  return std::cbrt(12.0 * transmissivity);
}

} // namespace rockjoint::flow
