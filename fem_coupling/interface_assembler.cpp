#include "interface_assembler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockjoint::fem
{

InterfaceAssembler::InterfaceAssembler(int gdim, int degree, QuadratureRule rule,
                                       std::span<const std::int32_t> minus_nodes,
                                       std::span<const std::int32_t> plus_nodes,
                                       std::span<const double> vertex_coordinates,
                                       std::span<const double> minus_interior_points,
                                       std::span<const std::int32_t> joint_tags,
                                       std::map<std::int32_t, JointBehaviour> behaviours)
    : _gdim(gdim), _quadrature(make_facet_quadrature(rule, gdim, degree)),
      _minus_nodes(minus_nodes.begin(), minus_nodes.end()),
      _plus_nodes(plus_nodes.begin(), plus_nodes.end()), _tags(joint_tags.begin(), joint_tags.end()),
      _behaviours(std::move(behaviours))
{
  const std::size_t np = _tags.size();
  const std::size_t nn = _quadrature.num_nodes;
  auto check_size = [&](std::size_t got, std::size_t want, const char* what)
  {
    if (got != want)
      throw std::invalid_argument(std::string("InterfaceAssembler: '") + what + "' has "
                                  + std::to_string(got) + " entries; expected "
                                  + std::to_string(want) + " for " + std::to_string(np)
                                  + " pairs");
  };
  check_size(_minus_nodes.size(), np * nn, "minus_nodes");
  check_size(_plus_nodes.size(), np * nn, "plus_nodes");
  check_size(vertex_coordinates.size(), np * gdim * gdim, "vertex_coordinates");
  check_size(minus_interior_points.size(), np * gdim, "minus_interior_points");
  for (std::size_t i = 0; i < np * nn; ++i)
  {
    if (_minus_nodes[i] < 0 || _plus_nodes[i] < 0 || _minus_nodes[i] == _plus_nodes[i])
      throw std::invalid_argument("InterfaceAssembler: pair " + std::to_string(i / nn)
                                  + " has a negative node index or a node shared by both "
                                    "sides (joint nodes must be split)");
    const auto largest = static_cast<std::size_t>(std::max(_minus_nodes[i], _plus_nodes[i]));
    _minimum_local_size = std::max(_minimum_local_size, (largest + 1) * std::size_t(gdim));
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
  _closure.assign(np * nq, 0.0);
  _normal_stress.assign(np * nq, 0.0);
  _shear_traction.assign(np * nq * (gdim - 1), 0.0);
  _status.assign(np * nq, static_cast<std::int32_t>(constitutive::Status::open));
}

void InterfaceAssembler::pair_dofs(std::int32_t p, std::span<std::int32_t> dofs) const
{
  const int nn = _quadrature.num_nodes;
  for (int a = 0; a < nn; ++a)
    for (int c = 0; c < _gdim; ++c)
    {
      dofs[a * _gdim + c] = _minus_nodes[p * nn + a] * _gdim + c;
      dofs[(nn + a) * _gdim + c] = _plus_nodes[p * nn + a] * _gdim + c;
    }
}

std::array<double, 3> InterfaceAssembler::local_jump(std::int32_t p, int q,
                                                     std::span<const double> u) const
{
  const int nn = _quadrature.num_nodes;
  std::array<double, 3> jump{}, local{};
  for (int a = 0; a < nn; ++a)
  {
    const double N = _quadrature.shape[q * nn + a];
    if (N == 0.0)
      continue;
    const std::size_t m = static_cast<std::size_t>(_minus_nodes[p * nn + a]) * _gdim;
    const std::size_t s = static_cast<std::size_t>(_plus_nodes[p * nn + a]) * _gdim;
    for (int c = 0; c < _gdim; ++c)
      jump[c] += N * (u[s + c] - u[m + c]);
  }
  const auto& Q = _frames[p].axes;
  for (int i = 0; i < _gdim; ++i)
    for (int c = 0; c < _gdim; ++c)
      local[i] += Q[i][c] * jump[c];
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
    for (int q = 0; q < nq; ++q)
    {
      const LocalResponse r = local_response(behaviour(p), _gdim, local_jump(p, q, u));
      const std::size_t point = static_cast<std::size_t>(p) * nq + q;
      _closure[point] = r.closure;
      _normal_stress[point] = r.normal_stress;
      _status[point] = static_cast<std::int32_t>(r.status);
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
        const std::size_t m = static_cast<std::size_t>(_minus_nodes[p * nn + a]) * _gdim;
        const std::size_t s = static_cast<std::size_t>(_plus_nodes[p * nn + a]) * _gdim;
        for (int c = 0; c < _gdim; ++c)
        {
          residual[s + c] += wN * T[c];
          residual[m + c] -= wN * T[c];
          finite = finite && std::isfinite(T[c]);
        }
      }
    }
  }
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
    const LocalResponse r = local_response(behaviour(p), g, local_jump(p, q, u));
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
        const double rate = -local_jump(p, q, du)[0]; // dΔ/dα
        if (rate > 0.0)
          alpha = std::min(alpha, fraction * std::max(limit - closure, 0.0) / rate);
      });
  return alpha;
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

} // namespace rockjoint::fem
