// SPDX-License-Identifier: MIT
#include "facet_quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rockjoint::fem_coupling
{

FacetQuadrature make_facet_quadrature(QuadratureRule rule, int gdim, int degree)
{
  if (gdim != 2 && gdim != 3)
    throw std::invalid_argument("make_facet_quadrature: gdim = " + std::to_string(gdim)
                                + " is invalid; it must be 2 or 3");
  if (degree != 1 && degree != 2)
    throw std::invalid_argument("make_facet_quadrature: element degree = "
                                + std::to_string(degree) + " is invalid; it must be 1 or 2");
  FacetQuadrature q;
  q.num_nodes = degree == 1 ? gdim : (gdim == 2 ? 3 : 6);
  const int n = q.num_nodes;

  if (rule == QuadratureRule::nodal)
  {
    if (degree == 1)
      q.weights.assign(n, 1.0 / n);
    else if (gdim == 2)
      q.weights = {1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0};
    else
      q.weights = {0.0, 0.0, 0.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
    q.shape.assign(n * n, 0.0);
    for (int a = 0; a < n; ++a)
      q.shape[a * n + a] = 1.0;
    // Node positions: vertices, then edge midpoints.
    q.barycentric.assign(n * gdim, 0.0);
    for (int v = 0; v < gdim; ++v)
      q.barycentric[v * gdim + v] = 1.0;
    if (degree == 2 && gdim == 2)
      q.barycentric[2 * 2 + 0] = q.barycentric[2 * 2 + 1] = 0.5;
    if (degree == 2 && gdim == 3)
    {
      const int edges[3][2] = {{1, 2}, {0, 2}, {0, 1}};
      for (int e = 0; e < 3; ++e)
        for (int v : edges[e])
          q.barycentric[(3 + e) * 3 + v] = 0.5;
    }
    return q;
  }

  if (degree != 1)
    throw std::invalid_argument("make_facet_quadrature: Gauss quadrature is implemented for "
                                "P1 only; use the nodal rule for P2");
  if (gdim == 2)
  {
    const double s = 0.5 / std::sqrt(3.0);
    for (double xi : {0.5 - s, 0.5 + s})
    {
      q.weights.push_back(0.5);
      q.shape.insert(q.shape.end(), {1.0 - xi, xi});
    }
  }
  else
  {
    // Strang-Fix 3-point rule, barycentric (2/3, 1/6, 1/6) and permutations.
    const double a = 2.0 / 3.0, b = 1.0 / 6.0;
    q.weights.assign(3, 1.0 / 3.0);
    q.shape = {a, b, b, b, a, b, b, b, a};
  }
  q.barycentric = q.shape; // P1: shape functions are the barycentric coordinates
  return q;
}

} // namespace rockjoint::fem_coupling
