// SPDX-License-Identifier: MIT
#include "interface_assembler.hpp"

#include <rockjoint/joint/joint_slip.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockjoint::fem_coupling
{

namespace
{
/// Throw std::invalid_argument (naming the method `who`, the argument and the entry) unless
/// `values` has one finite entry per joint point (`points`).
void check_point_values(const char* who, const char* name, std::span<const double> values,
                        std::size_t points, const char* unit)
{
  const std::string where = std::string("InterfaceAssembler::") + who + ": ";
  if (values.size() != points)
    throw std::invalid_argument(where + "'" + name + "' has " + std::to_string(values.size())
                                + " entries; expected " + std::to_string(points)
                                + " (one per joint point)");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw std::invalid_argument(where + "entry " + std::to_string(i) + " is "
                                  + std::to_string(values[i]) + "; it must be finite [" + unit + "]");
}
} // namespace

InterfaceAssembler::InterfaceAssembler(int gdim, int degree, QuadratureRule rule,
                                       std::span<const std::int32_t> pair_dofs,
                                       std::span<const double> vertex_coordinates,
                                       std::span<const double> minus_interior_points,
                                       std::span<const std::int32_t> joint_tags,
                                       std::map<std::int32_t, joint::JointBehaviour> behaviours)
    : _gdim(gdim), _quadrature(make_facet_quadrature(rule, gdim, degree)),
      _pair_dofs(pair_dofs.begin(), pair_dofs.end()), _tags(joint_tags.begin(), joint_tags.end()),
      _behaviours(std::move(behaviours))
{
  const std::size_t np = _tags.size();
  const std::size_t half = static_cast<std::size_t>(_quadrature.num_nodes) * gdim;
  auto check_size = [&](std::size_t got, std::size_t want, const char* what)
  {
    if (got != want)
      throw std::invalid_argument(std::string("InterfaceAssembler: '") + what + "' has "
                                  + std::to_string(got) + " entries; expected "
                                  + std::to_string(want) + " for " + std::to_string(np)
                                  + " pairs");
  };
  check_size(_pair_dofs.size(), np * 2 * half, "pair_dofs");
  check_size(vertex_coordinates.size(), np * gdim * gdim, "vertex_coordinates");
  check_size(minus_interior_points.size(), np * gdim, "minus_interior_points");
  for (std::size_t p = 0; p < np; ++p)
    for (std::size_t i = 0; i < half; ++i)
    {
      const std::int32_t m = _pair_dofs[2 * half * p + i], s = _pair_dofs[2 * half * p + half + i];
      if (m < 0 || s < 0 || m == s)
        throw std::invalid_argument("InterfaceAssembler: pair " + std::to_string(p)
                                    + " has a negative dof index or a dof shared by both sides ("
                                    + std::to_string(m) + ", " + std::to_string(s)
                                    + "; joint nodes must be split)");
      _minimum_local_size
          = std::max(_minimum_local_size, static_cast<std::size_t>(std::max(m, s)) + 1);
    }

  for (const auto& [tag, b] : _behaviours)
    validate(b, "tag " + std::to_string(tag));
  _pair_behaviour.reserve(np);
  for (std::int32_t tag : _tags)
  {
    auto it = _behaviours.find(tag);
    if (it == _behaviours.end())
    {
      std::string known;
      for (const auto& kv : _behaviours)
        known += (known.empty() ? "" : ", ") + std::to_string(kv.first);
      throw std::invalid_argument("InterfaceAssembler: no joint behaviour for joint tag "
                                  + std::to_string(tag) + " (behaviours given for tags: "
                                  + (known.empty() ? "none" : known) + ")");
    }
    _pair_behaviour.push_back(&it->second);
  }

  _frames.reserve(np);
  const std::size_t nq = _quadrature.num_points();
  _point_coordinates.assign(np * nq * gdim, 0.0);
  for (std::size_t p = 0; p < np; ++p)
  {
    auto verts = vertex_coordinates.subspan(p * gdim * gdim, gdim * gdim);
    _frames.push_back(facet_frame(gdim, verts, minus_interior_points.subspan(p * gdim, gdim)));
    for (std::size_t q = 0; q < nq; ++q)
      for (int v = 0; v < gdim; ++v)
        for (int c = 0; c < gdim; ++c)
          _point_coordinates[(p * nq + q) * gdim + c]
              += _quadrature.barycentric[q * gdim + v] * verts[v * gdim + c];
  }
  // One tangent frame per joint, from this process's pairs (the all-rank reference comes
  // through set_reference_directions).
  if (gdim == 3)
  {
    std::map<std::int32_t, std::array<double, 3>> directions;
    for (const auto& [tag, moment] : normal_moments())
      directions[tag] = joint_reference_direction(moment);
    set_reference_directions(directions);
  }
  _closure.assign(np * nq, 0.0);
  _normal_stress.assign(np * nq, 0.0);
  _shear_traction.assign(np * nq * (gdim - 1), 0.0);
  _status.assign(np * nq, static_cast<std::int32_t>(constitutive::Status::open));
  _shear_state.assign(np * nq, static_cast<std::int32_t>(joint::ShearState::stick));
  _initial_jump.assign(np * nq * gdim, 0.0);
  _pore_pressure.assign(np * nq, 0.0);
  _converged.assign(np * nq, joint::JointPointState{});
  _trial = _converged;
  _cached_response.assign(np * nq, joint::LocalResponse{});
  _cached_jump.assign(np * nq, std::array<double, 3>{});
}

void InterfaceAssembler::pair_dofs(std::int32_t p, std::span<std::int32_t> dofs) const
{
  const std::size_t n = pair_size();
  std::copy_n(_pair_dofs.begin() + p * n, n, dofs.begin());
}

std::array<double, 3> InterfaceAssembler::local_jump(std::int32_t p, int q,
                                                     std::span<const double> u,
                                                     bool with_initial) const
{
  const int nn = _quadrature.num_nodes;
  const std::int32_t* minus = _pair_dofs.data() + static_cast<std::size_t>(p) * pair_size();
  const std::int32_t* plus = minus + nn * _gdim;
  std::array<double, 3> jump{}, local{};
  for (int a = 0; a < nn; ++a)
  {
    const double N = _quadrature.shape[q * nn + a];
    if (N == 0.0)
      continue;
    for (int c = 0; c < _gdim; ++c)
      jump[c] += N * (u[plus[a * _gdim + c]] - u[minus[a * _gdim + c]]);
  }
  const auto& Q = _frames[p].axes;
  const std::size_t point = point_index(p, q);
  for (int i = 0; i < _gdim; ++i)
  {
    if (with_initial)
      local[i] = _initial_jump[point * _gdim + i];
    for (int c = 0; c < _gdim; ++c)
      local[i] += Q[i][c] * jump[c];
  }
  return local;
}

void InterfaceAssembler::check_local_array(const char* who, const char* array,
                                           std::size_t size) const
{
  if (size < _minimum_local_size)
    throw std::invalid_argument(std::string("InterfaceAssembler::") + who + ": '" + array
                                + "' has " + std::to_string(size)
                                + " entries; the joint pairs address local dofs up to "
                                + std::to_string(_minimum_local_size)
                                + " (the local array of the function space, ghosts included)");
}

bool InterfaceAssembler::assemble_residual(std::span<const double> u, std::span<double> residual)
{
  check_local_array("assemble_residual", "u", u.size());
  check_local_array("assemble_residual", "residual", residual.size());
  const int nn = _quadrature.num_nodes, nq = _quadrature.num_points();
  bool finite = true;
  for (std::int32_t p = 0; p < num_pairs(); ++p)
  {
    const auto& Q = _frames[p].axes;
    const std::int32_t* minus = _pair_dofs.data() + static_cast<std::size_t>(p) * pair_size();
    const std::int32_t* plus = minus + nn * _gdim;
    for (int q = 0; q < nq; ++q)
    {
      const std::size_t point = point_index(p, q);
      const std::array<double, 3> jump = local_jump(p, q, u);
      const joint::LocalResponse& r = _cached_response[point]
          = joint::joint_response(behaviour(p), _gdim, jump, _converged[point], _trial[point],
                                  _pore_pressure[point]);
      _cached_jump[point] = jump;
      ++_num_law_evaluations;
      _closure[point] = r.closure;
      _normal_stress[point] = r.normal_stress;
      _status[point] = static_cast<std::int32_t>(r.status);
      _shear_state[point] = static_cast<std::int32_t>(r.shear_state);
      for (int i = 1; i < _gdim; ++i)
        _shear_traction[point * (_gdim - 1) + i - 1] = r.traction[i];

      // Rotate back: T = Qᵀ t_local.
      std::array<double, 3> T{};
      for (int c = 0; c < _gdim; ++c)
        for (int i = 0; i < _gdim; ++i)
          T[c] += Q[i][c] * r.traction[i];
      const double w = _quadrature.weights[q] * _frames[p].measure;
      for (int a = 0; a < nn; ++a)
      {
        const double wN = w * _quadrature.shape[q * nn + a];
        if (wN == 0.0)
          continue;
        for (int c = 0; c < _gdim; ++c)
        {
          residual[plus[a * _gdim + c]] += wN * T[c];
          residual[minus[a * _gdim + c]] -= wN * T[c];
          finite = finite && std::isfinite(T[c]);
        }
      }
    }
  }
  _cache_valid = true;
  return finite;
}

void InterfaceAssembler::update_state(std::span<const double> u)
{
  std::vector<double> scratch(u.size(), 0.0);
  assemble_residual(u, scratch);
}

void InterfaceAssembler::pair_matrix(std::int32_t p, std::span<const double> u,
                                     std::span<double> matrix) const
{
  check_local_array("pair_matrix", "u", u.size());
  if (p < 0 || p >= num_pairs())
    throw std::out_of_range("InterfaceAssembler::pair_matrix: pair " + std::to_string(p)
                            + " is not in [0, " + std::to_string(num_pairs()) + ")");
  if (matrix.size() < static_cast<std::size_t>(pair_size()) * pair_size())
    throw std::invalid_argument("InterfaceAssembler::pair_matrix: 'matrix' has "
                                + std::to_string(matrix.size()) + " entries; pair_size()² = "
                                + std::to_string(pair_size() * pair_size()) + " are needed");
  const int nn = _quadrature.num_nodes, nq = _quadrature.num_points(), g = _gdim;
  const int n = pair_size();
  std::fill(matrix.begin(), matrix.begin() + n * n, 0.0);
  const auto& Q = _frames[p].axes;
  for (int q = 0; q < nq; ++q)
  {
    // Reuse the response of the last residual if this point's jump is bit-identical to the
    // one it was evaluated at; else evaluate from the converged state (scratch trial).
    const std::size_t point = point_index(p, q);
    const std::array<double, 3> jump = local_jump(p, q, u);
    const bool cached = _cache_valid && jump == _cached_jump[point];
    joint::LocalResponse evaluated;
    if (!cached)
    {
      joint::JointPointState trial;
      evaluated = joint::joint_response(behaviour(p), g, jump, _converged[point], trial,
                                        _pore_pressure[point]);
      ++_num_law_evaluations;
    }
    const joint::LocalResponse& r = cached ? _cached_response[point] : evaluated;
    // D = Qᵀ (∂t/∂j) Q: global traction derivative w.r.t. the global jump.
    double D[3][3] = {};
    for (int c = 0; c < g; ++c)
      for (int d = 0; d < g; ++d)
        for (int i = 0; i < g; ++i)
          for (int j = 0; j < g; ++j)
            D[c][d] += Q[i][c] * r.tangent[i][j] * Q[j][d];
    const double w = _quadrature.weights[q] * _frames[p].measure;
    for (int a = 0; a < nn; ++a)
    {
      const double Na = _quadrature.shape[q * nn + a];
      if (Na == 0.0)
        continue;
      for (int b = 0; b < nn; ++b)
      {
        const double wNN = w * Na * _quadrature.shape[q * nn + b];
        if (wNN == 0.0)
          continue;
        // Sides: 0 = minus (sign -1), 1 = plus (sign +1): ∂[[u]]/∂u_side = ±N.
        for (int sa = 0; sa < 2; ++sa)
          for (int sb = 0; sb < 2; ++sb)
          {
            const double sign = (sa == sb) ? wNN : -wNN;
            const int row0 = (sa * nn + a) * g, col0 = (sb * nn + b) * g;
            for (int c = 0; c < g; ++c)
              for (int d = 0; d < g; ++d)
                matrix[(row0 + c) * n + col0 + d] += sign * D[c][d];
          }
      }
    }
  }
}

double InterfaceAssembler::maximum_closure_ratio(std::span<const double> u) const
{
  check_local_array("maximum_closure_ratio", "u", u.size());
  double ratio = 0.0;
  for_each_limited_point(
      [&](std::int32_t p, int q, double limit)
      {
        const double r = -local_jump(p, q, u)[0] / limit;
        ratio = std::isnan(r) ? std::numeric_limits<double>::infinity() : std::max(ratio, r);
      });
  return ratio;
}

double InterfaceAssembler::admissible_step_length(std::span<const double> u,
                                                  std::span<const double> du,
                                                  double fraction) const
{
  check_local_array("admissible_step_length", "u", u.size());
  check_local_array("admissible_step_length", "du", du.size());
  double alpha = 1.0;
  for_each_limited_point(
      [&](std::int32_t p, int q, double limit)
      {
        const double closure = -local_jump(p, q, u)[0];
        const double rate = -local_jump(p, q, du, false)[0]; // dΔ/dα
        if (rate > 0.0)
          alpha = std::min(alpha, fraction * std::max(limit - closure, 0.0) / rate);
      });
  return alpha;
}

std::map<std::int32_t, std::array<double, 9>> InterfaceAssembler::normal_moments() const
{
  std::map<std::int32_t, std::array<double, 9>> moments;
  for (std::size_t p = 0; p < _frames.size(); ++p)
  {
    auto& M = moments[_tags[p]];
    const auto& n = _frames[p].axes[0];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        M[3 * i + j] += _frames[p].measure * n[i] * n[j];
  }
  return moments;
}

void InterfaceAssembler::set_reference_directions(
    const std::map<std::int32_t, std::array<double, 3>>& directions)
{
  for (std::size_t p = 0; p < _frames.size(); ++p)
    if (auto it = directions.find(_tags[p]); it != directions.end())
      set_tangents(_frames[p], _gdim, it->second);
  _cache_valid = false;
}

void InterfaceAssembler::set_pore_pressure(std::span<const double> pressure)
{
  check_point_values("set_pore_pressure", "pressure", pressure, _pore_pressure.size(), "Pa");
  std::copy(pressure.begin(), pressure.end(), _pore_pressure.begin());
  _cache_valid = false;
}

void InterfaceAssembler::set_initial_jump(std::span<const double> initial_jump)
{
  if (initial_jump.size() != _initial_jump.size())
    throw std::invalid_argument("InterfaceAssembler::set_initial_jump: 'initial_jump' has "
                                + std::to_string(initial_jump.size()) + " entries; expected "
                                + std::to_string(_initial_jump.size()) + " (points × gdim = "
                                + std::to_string(_closure.size()) + " × " + std::to_string(_gdim)
                                + ")");
  for (std::size_t i = 0; i < initial_jump.size(); ++i)
    if (!std::isfinite(initial_jump[i]))
      throw std::invalid_argument("InterfaceAssembler::set_initial_jump: entry "
                                  + std::to_string(i) + " (point " + std::to_string(i / _gdim)
                                  + ", component " + std::to_string(i % _gdim) + ") is "
                                  + std::to_string(initial_jump[i]) + "; it must be finite [m]");
  std::copy(initial_jump.begin(), initial_jump.end(), _initial_jump.begin());
  // A joint pre-closed by the in-situ stress was loaded to that closure on its virgin curve:
  // a hysteretic law unloads from there (largest closure reached >= the initial closure).
  for (std::size_t p = 0; p < _converged.size(); ++p)
  {
    const double closure = -_initial_jump[p * _gdim];
    _converged[p].maximum_closure = std::max(_converged[p].maximum_closure, closure);
    _trial[p].maximum_closure = std::max(_trial[p].maximum_closure, closure);
  }
  _cache_valid = false;
}

void InterfaceAssembler::set_maximum_closure(std::span<const double> maximum_closure)
{
  check_point_values("set_maximum_closure", "maximum_closure", maximum_closure, _converged.size(), "m");
  for (std::size_t p = 0; p < maximum_closure.size(); ++p)
    _converged[p].maximum_closure = _trial[p].maximum_closure = maximum_closure[p];
  _cache_valid = false;
}

void InterfaceAssembler::commit_state()
{
  _converged = _trial;
  _cache_valid = false;
}

void InterfaceAssembler::revert_state()
{
  _trial = _converged;
  _cache_valid = false;
}

void InterfaceAssembler::reset_state()
{
  std::fill(_converged.begin(), _converged.end(), joint::JointPointState{});
  for (std::size_t p = 0; p < _converged.size(); ++p) // the in-situ closure was reached (above)
    _converged[p].maximum_closure = std::max(0.0, -_initial_jump[p * _gdim]);
  revert_state();
}

std::vector<double> InterfaceAssembler::normals() const
{
  std::vector<double> n(_frames.size() * _gdim);
  for (std::size_t p = 0; p < _frames.size(); ++p)
    for (int c = 0; c < _gdim; ++c)
      n[p * _gdim + c] = _frames[p].axes[0][c];
  return n;
}

std::vector<std::int32_t> InterfaceAssembler::point_tags() const
{
  std::vector<std::int32_t> t;
  t.reserve(_closure.size());
  for (std::int32_t tag : _tags)
    t.insert(t.end(), _quadrature.num_points(), tag);
  return t;
}

std::vector<double> InterfaceAssembler::measures() const
{
  std::vector<double> m;
  m.reserve(_frames.size());
  for (const auto& f : _frames)
    m.push_back(f.measure);
  return m;
}

} // namespace rockjoint::fem_coupling
