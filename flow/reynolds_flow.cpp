// SPDX-License-Identifier: MIT
#include "reynolds_flow.hpp"

#include "connectivity.hpp"

#ifdef ROCKJOINT_WITH_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockjoint::flow
{

namespace
{
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

[[noreturn]] void fail(const std::string& what)
{
  throw std::invalid_argument("flow::transmissivity: " + what);
}

void check_grid(std::size_t rows, std::size_t cols, double spacing_x, double spacing_y,
                const FlowOptions& options)
{
  if (rows < 2 || cols < 2)
    fail("the aperture grid is " + std::to_string(rows) + " x " + std::to_string(cols)
         + "; it needs at least 2 rows and 2 columns");
  for (const auto& [name, h] : {std::pair{"spacing_x", spacing_x}, {"spacing_y", spacing_y}})
    if (!(std::isfinite(h) && h > 0.0))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << name << " = " << h << " m must be finite and > 0";
      fail(msg.str());
    }
  if (options.solver == LinearSolver::conjugate_gradient
      && (!(options.tolerance > 0.0 && options.tolerance < 1.0) || options.maximum_iterations < 1))
    fail("FlowOptions: CG tolerance must be in (0, 1) and maximum_iterations >= 1");
}

void check_field(std::span<const double> aperture, std::size_t rows, std::size_t cols)
{
  if (aperture.size() != rows * cols)
    fail("the aperture field has " + std::to_string(aperture.size()) + " values; rows x cols = "
         + std::to_string(rows) + " x " + std::to_string(cols) + " needs "
         + std::to_string(rows * cols));
  bool scanned = false;
  for (std::size_t k = 0; k < aperture.size(); ++k)
  {
    const double e = aperture[k];
    if (std::isnan(e))
      continue;
    if (!(e >= 0.0) || std::isinf(e))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "aperture (row " << k / cols << ", column " << k % cols << ") = " << e
          << " m; an aperture must be finite and >= 0 (NaN marks a point not scanned)";
      fail(msg.str());
    }
    scanned = true;
  }
  if (!scanned)
    fail("every aperture is NaN: no scanned point");
}

/// Cells whose conductance k = e³/12 is below this fraction of the largest cell's are closed
/// (e < 1e-4 e_max): the double-precision system cannot resolve them. A region of open cells
/// that reaches the inlet (or its pinned cell) only through such cells has a pivot of their
/// size computed by cancellation of O(1) terms, so it comes out as round-off, possibly
/// negative: CHOLMOD stopped ("not positive definite") and LDLᵀ returned T < 0 on fields with
/// 40-70 % clustered cells at e <= 1e-9 m (issue 39; tests/python/test_flow_contact_set.py).
/// What they carry is below 1e-12 k_max per unit gradient, far under any T this solver reports.
constexpr double resolved_conductance = 1e-12;

/// Harmonic mean of two cell conductances: the two half cells in series (file comment of the
/// header); 0 if either cell is closed.
double face_conductance(double a, double b)
{
  return a > 0.0 && b > 0.0 ? 2.0 * a * b / (a + b) : 0.0;
}

/// The grid's cells and faces, conductances scaled by the largest cell's k_max = e_max³/12
/// (the system is then O(1) whatever the aperture's unit; T is scaled back at the end).
struct Grid
{
  std::size_t rows, cols;
  double hx, hy;
  bool periodic;
  std::vector<double> cell;   ///< k/k_max of each cell (0: closed or masked)
  std::vector<double> face_x; ///< between cell k and its +x neighbour (wrapped if periodic)
  std::vector<double> face_y; ///< between cell k and its +y neighbour
  double k_max = 0.0;         ///< [m³]

  std::size_t east(std::size_t k) const { return k % cols + 1 < cols ? k + 1 : k + 1 - cols; }
  std::size_t north(std::size_t k) const
  {
    return k / cols + 1 < rows ? k + cols : k + cols - rows * cols;
  }
  bool has_east(std::size_t k) const { return periodic || k % cols + 1 < cols; }
  bool has_north(std::size_t k) const { return periodic || k / cols + 1 < rows; }
};

/// One imposed gradient ∇p̄ = -e_axis (axis 0: x, 1: y).
struct Load
{
  int axis;
  double length(const Grid& g) const { return axis == 0 ? g.hx : g.hy; } ///< cell length along it
};

/// The pressure system of one load on the whole grid: the cells in the flow (`active`) either
/// solved for (`unknown`) or pinned, every other cell an identity row with right-hand side 0.
struct System
{
  SparseMatrix matrix;
  std::vector<unsigned char> active;  ///< in the flow: solved for, or pinned (periodic)
  std::vector<unsigned char> unknown; ///< solved for
  std::size_t size = 0;               ///< number of unknowns
};

/// Face weight: conductance times the cross-section over the distance (h_y/h_x for an x face).
double weight_x(const Grid& g, std::size_t k) { return g.face_x[k] * g.hy / g.hx; }
double weight_y(const Grid& g, std::size_t k) { return g.face_y[k] * g.hx / g.hy; }

/// Inlet and outlet half cells of a sealed-sides load: conductance k_i over h/2, times the
/// cross-section (2 k_i h_y/h_x for the x load).
double boundary_weight(const Grid& g, const Load& load, std::size_t k)
{
  return load.axis == 0 ? 2.0 * g.cell[k] * g.hy / g.hx : 2.0 * g.cell[k] * g.hx / g.hy;
}
bool on_inlet(const Grid& g, const Load& load, std::size_t k)
{
  return load.axis == 0 ? k % g.cols == 0 : k / g.cols == 0;
}
bool on_outlet(const Grid& g, const Load& load, std::size_t k)
{
  return load.axis == 0 ? k % g.cols + 1 == g.cols : k / g.cols + 1 == g.rows;
}

/// The 5-point finite-volume operator on the `active` cells, one cell per region pinned
/// (periodic) or the inlet and outlet half cells on the diagonal (sealed sides). Every face of
/// the grid keeps its two off-diagonal entries (0 where it couples no two unknowns), so every
/// system of a grid has one sparsity pattern and one symbolic factorisation.
System assemble(const Grid& g, std::vector<unsigned char> active, const OpenRegions& regions,
                const Load* sealed_load)
{
  // Periodic: each region's most conductive cell is pinned (φ = 0), the best-conditioned choice.
  std::vector<std::size_t> pins(regions.first_cell);
  for (std::size_t k = 0; k < g.rows * g.cols; ++k)
    if (regions.label[k] >= 0 && g.cell[k] > g.cell[pins[std::size_t(regions.label[k])]])
      pins[std::size_t(regions.label[k])] = k;
  const std::size_t n = g.rows * g.cols;
  System s;
  s.active = std::move(active);
  s.unknown.assign(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    const bool pinned = g.periodic && s.active[k] && pins[std::size_t(regions.label[k])] == k;
    s.unknown[k] = s.active[k] && !pinned;
    s.size += s.unknown[k];
  }
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(7 * n);
  auto couple = [&](std::size_t a, std::size_t b, double w)
  {
    const double off = s.unknown[a] && s.unknown[b] ? -w : 0.0;
    entries.emplace_back(int(a), int(b), off);
    entries.emplace_back(int(b), int(a), off);
    if (s.unknown[a])
      entries.emplace_back(int(a), int(a), w);
    if (s.unknown[b])
      entries.emplace_back(int(b), int(b), w);
  };
  for (std::size_t k = 0; k < n; ++k)
  {
    entries.emplace_back(int(k), int(k), s.unknown[k] ? 0.0 : 1.0);
    // Both cells of an open face are in one region, so both are active or neither.
    if (g.has_east(k))
      couple(k, g.east(k), s.active[k] ? weight_x(g, k) : 0.0);
    if (g.has_north(k))
      couple(k, g.north(k), s.active[k] ? weight_y(g, k) : 0.0);
    // (at least 2 cells along the load: no cell is on both the inlet and the outlet)
    if (sealed_load && s.unknown[k]
        && (on_inlet(g, *sealed_load, k) || on_outlet(g, *sealed_load, k)))
      entries.emplace_back(int(k), int(k), boundary_weight(g, *sealed_load, k));
  }
  s.matrix.resize(int(n), int(n));
  s.matrix.setFromTriplets(entries.begin(), entries.end());
  return s;
}

/// Right-hand side of `load`: periodic, the jump of ∇p̄·x across the faces normal to the load
/// (p = ∇p̄·x + φ, so a face carries w (φ_a - φ_b + h) for ∇p̄ = -e_axis); sealed sides, the
/// inlet pressure L (unit gradient over the grid's length) through the inlet half cells.
Eigen::VectorXd right_hand_side(const Grid& g, const System& s, const Load& load)
{
  const std::size_t n = g.rows * g.cols;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(Eigen::Index(n));
  if (g.periodic)
  {
    const bool x = load.axis == 0;
    const double h = load.length(g);
    for (std::size_t k = 0; k < n; ++k)
    {
      if (!s.active[k])
        continue;
      const double w = x ? weight_x(g, k) : weight_y(g, k);
      if (w == 0.0)
        continue;
      const std::size_t m = x ? g.east(k) : g.north(k);
      if (s.unknown[k])
        b[Eigen::Index(k)] -= w * h;
      if (s.unknown[m])
        b[Eigen::Index(m)] += w * h;
    }
  }
  else
  {
    const double inlet = load.axis == 0 ? double(g.cols) * g.hx : double(g.rows) * g.hy;
    for (std::size_t k = 0; k < n; ++k)
      if (s.unknown[k] && on_inlet(g, load, k))
        b[Eigen::Index(k)] += boundary_weight(g, load, k) * inlet;
  }
  return b;
}

/// Pressure of every cell: the solution where solved, 0 at a pinned cell (periodic: φ; sealed
/// sides: p), NaN where not active.
std::vector<double> cell_pressures(const System& s, const Eigen::VectorXd& x)
{
  std::vector<double> p(s.unknown.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < p.size(); ++k)
    if (s.active[k])
      p[k] = s.unknown[k] ? x[Eigen::Index(k)] : 0.0;
  return p;
}

/// Mean flux per unit width over the grid's rectangle [m³ per unit gradient, times μ], along x
/// and y, from the cell pressures of `load`: Σ over the faces of the face flux per unit width
/// times the face's share h_x h_y of the area, over the area. Sealed sides along the load: the
/// inflow and outflow (equal at convergence; their mean), which also counts the two half cells.
std::array<double, 2> mean_flux(const Grid& g, const System& s, const Load& load,
                                const std::vector<double>& p)
{
  const std::size_t n = g.rows * g.cols;
  const double jump_x = g.periodic && load.axis == 0 ? g.hx : 0.0;
  const double jump_y = g.periodic && load.axis == 1 ? g.hy : 0.0;
  double sum_x = 0.0, sum_y = 0.0, inflow = 0.0, outflow = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!s.active[k])
      continue;
    if (g.has_east(k) && g.face_x[k] > 0.0)
      sum_x += g.face_x[k] * (p[k] - p[g.east(k)] + jump_x) / g.hx;
    if (g.has_north(k) && g.face_y[k] > 0.0)
      sum_y += g.face_y[k] * (p[k] - p[g.north(k)] + jump_y) / g.hy;
    if (!g.periodic)
    {
      const double inlet = load.axis == 0 ? double(g.cols) * g.hx : double(g.rows) * g.hy;
      if (on_inlet(g, load, k))
        inflow += boundary_weight(g, load, k) * (inlet - p[k]);
      if (on_outlet(g, load, k))
        outflow += boundary_weight(g, load, k) * p[k];
    }
  }
  std::array<double, 2> q{sum_x / double(n), sum_y / double(n)};
  if (!g.periodic)
  {
    const double width = load.axis == 0 ? double(g.rows) * g.hy : double(g.cols) * g.hx;
    q[std::size_t(load.axis)] = 0.5 * (inflow + outflow) / width;
  }
  return q;
}

/// A transmissivity that is not finite, or a negative principal term, comes from a pressure
/// system that was not solved: an error, never an aperture (issue 39: LDLᵀ gave T = -3e-27 m³).
void check_transmissivity(const FlowResult& r)
{
  static constexpr const char* name[4] = {"T_xx", "T_xy", "T_yx", "T_yy"};
  for (std::size_t i = 0; i < 4; ++i)
    if (!std::isfinite(r.transmissivity[i]) || ((i == 0 || i == 3) && r.transmissivity[i] < 0.0))
    {
      std::ostringstream msg;
      msg.precision(6);
      msg << "flow::transmissivity: " << name[i] << " = " << r.transmissivity[i]
          << " m³ is not a transmissivity (finite, and >= 0 on the diagonal): the pressure system"
          << " was not solved (relative residual " << r.relative_residual << ")";
      throw std::runtime_error(msg.str());
    }
}

struct Solved
{
  std::vector<Eigen::VectorXd> x;
  std::vector<int> iterations;
  double residual = 0.0;
  bool converged = true;
  bool direct_fallback = false; ///< CG stalled: solved by the supernodal factorisation
};

} // namespace

/// The linear solver of FlowOptions over the systems of one grid: the symbolic analysis of the
/// first system serves the next ones (one pattern per grid, see assemble).
class detail::PressureSolver
{
public:
  explicit PressureSolver(const FlowOptions& options) : _options(options) {}

  /// Solve A x = b for each right-hand side with one factorisation (or one preconditioner).
  Solved solve(const SparseMatrix& a, const std::vector<Eigen::VectorXd>& rhs)
  {
    Solved out;
    switch (_options.solver)
    {
    case LinearSolver::cholesky:
      direct(_cholesky, a, rhs, out);
      break;
    case LinearSolver::simplicial_cholesky:
      direct(_ldlt, a, rhs, out);
      break;
    case LinearSolver::conjugate_gradient:
      _cg.setTolerance(_options.tolerance);
      _cg.setMaxIterations(_options.maximum_iterations);
      _cg.compute(a);
      for (const auto& b : rhs)
      {
        out.x.push_back(_cg.solve(b));
        out.iterations.push_back(int(_cg.iterations()));
        out.converged = out.converged && _cg.info() == Eigen::Success;
      }
      break;
    }
    out.residual = residual(a, rhs, out.x);
    if (_options.solver == LinearSolver::conjugate_gradient)
    {
      out.converged = out.converged && out.residual <= 10.0 * _options.tolerance;
      if (!out.converged)
      {
        // Near percolation the conductances of the resolved cells span up to 12 decades and
        // incomplete-Cholesky CG stalls (the tight joint of tests/python/test_flow_contact_set.py:
        // 10000 iterations, residual 5e-6 to 3e-4 at 72-125 MPa): the supernodal factorisation
        // solves the same system instead, and the result says so (FlowResult::direct_fallback).
        Solved exact;
        direct(_cholesky, a, rhs, exact);
        exact.residual = residual(a, rhs, exact.x);
        exact.iterations = out.iterations;
        exact.direct_fallback = true;
        out = std::move(exact);
      }
    }
    return out;
  }

private:
  static double residual(const SparseMatrix& a, const std::vector<Eigen::VectorXd>& rhs,
                         const std::vector<Eigen::VectorXd>& x)
  {
    double largest = 0.0;
    for (std::size_t r = 0; r < rhs.size(); ++r)
    {
      const double norm = rhs[r].norm();
      if (norm > 0.0)
        largest = std::max(largest, (a * x[r] - rhs[r]).norm() / norm);
    }
    return largest;
  }

  template <class Factorisation>
  void direct(Factorisation& f, const SparseMatrix& a, const std::vector<Eigen::VectorXd>& rhs,
              Solved& out)
  {
    if (!_analysed)
      f.analyzePattern(a);
    _analysed = true;
    f.factorize(a);
    out.converged = f.info() == Eigen::Success;
    for (const auto& b : rhs)
    {
      out.x.push_back(out.converged ? Eigen::VectorXd(f.solve(b)) : Eigen::VectorXd::Zero(b.size()));
      out.iterations.push_back(0);
    }
  }

  FlowOptions _options;
  bool _analysed = false;
#ifdef ROCKJOINT_WITH_CHOLMOD
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> _cholesky;
#else // ROCKJOINT_CHOLMOD=OFF: Eigen's simplicial LLᵀ, the same factor without GPL code
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> _cholesky;
#endif
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> _ldlt;
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>
      _cg;
};

ReynoldsFlow::ReynoldsFlow(std::size_t rows, std::size_t cols, double spacing_x,
                           double spacing_y, Boundary boundary, const FlowOptions& options)
    : _rows(rows), _cols(cols), _hx(spacing_x), _hy(spacing_y), _boundary(boundary),
      _options(options)
{
  check_grid(rows, cols, spacing_x, spacing_y, options);
  _solver = std::make_unique<detail::PressureSolver>(options);
}

ReynoldsFlow::~ReynoldsFlow() = default;
ReynoldsFlow::ReynoldsFlow(ReynoldsFlow&&) noexcept = default;
ReynoldsFlow& ReynoldsFlow::operator=(ReynoldsFlow&&) noexcept = default;

FlowResult transmissivity(std::span<const double> aperture, std::size_t rows, std::size_t cols,
                          double spacing_x, double spacing_y, Boundary boundary,
                          const FlowOptions& options)
{
  return ReynoldsFlow(rows, cols, spacing_x, spacing_y, boundary, options).transmissivity(aperture);
}

FlowResult ReynoldsFlow::transmissivity(std::span<const double> aperture)
{
  const std::size_t rows = _rows, cols = _cols;
  check_field(aperture, rows, cols);
  const std::size_t n = rows * cols;
  Grid g{rows, cols, _hx, _hy, _boundary == Boundary::periodic, {}, {}, {}};

  FlowResult result;
  double e_max = 0.0, e_sum = 0.0;
  std::size_t scanned = 0, open = 0;
  for (const double e : aperture)
    if (!std::isnan(e))
    {
      ++scanned;
      e_sum += e;
      open += e > 0.0;
      e_max = std::max(e_max, e);
    }
  result.mechanical_aperture = e_sum / double(scanned);
  result.open_fraction = double(open) / double(scanned);
  if (e_max == 0.0)
    return result; // every scanned point closed: no flow

  // k = e³/12 (local cubic law), scaled by k_max.
  g.k_max = e_max * e_max * e_max / 12.0;
  g.cell.resize(n);
  std::vector<unsigned char> is_open(n), open_x(n, 0), open_y(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double e = aperture[k];
    const double c = std::isnan(e) ? 0.0 : (e / e_max) * (e / e_max) * (e / e_max);
    g.cell[k] = c >= resolved_conductance ? c : 0.0;
    is_open[k] = g.cell[k] > 0.0;
  }
  g.face_x.assign(n, 0.0);
  g.face_y.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (g.has_east(k))
      g.face_x[k] = face_conductance(g.cell[k], g.cell[g.east(k)]);
    if (g.has_north(k))
      g.face_y[k] = face_conductance(g.cell[k], g.cell[g.north(k)]);
    open_x[k] = g.face_x[k] > 0.0;
    open_y[k] = g.face_y[k] > 0.0;
  }
  const OpenRegions regions = open_regions(is_open, open_x, open_y, rows, cols, g.periodic);
  for (std::size_t r = 0; r < regions.count(); ++r)
  {
    result.percolates[0] = result.percolates[0] || regions.spans_x[r];
    result.percolates[1] = result.percolates[1] || regions.spans_y[r];
  }
  auto active_cells = [&](bool along_x, bool along_y)
  {
    std::vector<unsigned char> active(n, 0);
    for (std::size_t k = 0; k < n; ++k)
      if (regions.label[k] >= 0)
      {
        const auto r = std::size_t(regions.label[k]);
        active[k] = (along_x && regions.spans_x[r]) || (along_y && regions.spans_y[r]);
      }
    return active;
  };

  std::array<double, 4> t{}; // scaled by k_max
  detail::PressureSolver& solver = *_solver;
  auto record = [&](const Solved& solved)
  {
    result.relative_residual = std::max(result.relative_residual, solved.residual);
    result.converged = result.converged && solved.converged;
    result.direct_fallback = result.direct_fallback || solved.direct_fallback;
  };
  if (g.periodic)
  {
    // One system for both gradients: the regions that wind along x or y, one cell of each
    // pinned. A region winding along y only carries no x flux (to round-off).
    const System s = assemble(g, active_cells(true, true), regions, nullptr);
    result.unknowns = s.size;
    std::vector<Load> loads;
    for (int axis = 0; axis < 2; ++axis)
      if (result.percolates[std::size_t(axis)])
        loads.push_back(Load{axis});
    if (!loads.empty() && s.size > 0)
    {
      std::vector<Eigen::VectorXd> rhs;
      for (const Load& load : loads)
        rhs.push_back(right_hand_side(g, s, load));
      const Solved solved = solver.solve(s.matrix, rhs);
      record(solved);
      for (std::size_t l = 0; l < loads.size(); ++l)
      {
        const auto a = std::size_t(loads[l].axis);
        const auto q = mean_flux(g, s, loads[l], cell_pressures(s, solved.x[l]));
        t[a] = q[0];     // column a: (T_xa, T_ya)
        t[2 + a] = q[1];
        result.iterations[a] = solved.iterations[l];
      }
    }
    // Without a path along an axis no flux crosses it under either gradient: exactly 0.
    for (std::size_t a = 0; a < 2; ++a)
      if (!result.percolates[a])
        t[2 * a] = t[2 * a + 1] = t[a] = t[2 + a] = 0.0;
  }
  else
  {
    for (int axis = 0; axis < 2; ++axis)
    {
      const auto a = std::size_t(axis);
      if (!result.percolates[a])
        continue; // no region joins the inlet to the outlet: T column 0
      const Load load{axis};
      const System s = assemble(g, active_cells(axis == 0, axis == 1), regions, &load);
      result.unknowns = std::max(result.unknowns, s.size);
      const Solved solved = solver.solve(s.matrix, {right_hand_side(g, s, load)});
      record(solved);
      const auto q = mean_flux(g, s, load, cell_pressures(s, solved.x[0]));
      t[a] = q[0];
      t[2 + a] = q[1];
      result.iterations[a] = solved.iterations[0];
    }
  }
  for (std::size_t i = 0; i < 4; ++i)
    result.transmissivity[i] = g.k_max * t[i];
  check_transmissivity(result);
  return result;
}

} // namespace rockjoint::flow
