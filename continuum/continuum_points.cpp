// SPDX-License-Identifier: MIT
#include "continuum_points.hpp"

#include <stdexcept>
#include <string>

namespace rockjoint::continuum
{

ContinuumPoints::ContinuumPoints(EquivalentContinuum material, std::size_t num_points)
    : _material(std::move(material)), _num_points(num_points),
      _converged(num_points * _material.num_sets()), _trial(_converged)
{
}

std::size_t ContinuumPoints::evaluate(std::span<const double> strain, std::span<double> stress,
                                      std::span<double> tangent)
{
  return evaluate_points(_material, strain, _converged, _trial, stress, tangent);
}

void ContinuumPoints::initialise_from_stress(std::span<const double> stress,
                                             std::span<double> strain)
{
  const std::size_t nv = static_cast<std::size_t>(_material.strain_size());
  const std::size_t ns = _material.num_sets();
  if (stress.size() != _num_points * nv || strain.size() != _num_points * nv)
    throw std::invalid_argument("ContinuumPoints::initialise_from_stress: expected "
                                + std::to_string(_num_points) + " × " + std::to_string(nv)
                                + " stress and strain entries");
  for (std::size_t p = 0; p < _num_points; ++p)
  {
    std::span<SetState> states(_converged.data() + p * ns, ns);
    for (SetState& s : states)
      s = SetState{};
    std::vector<double> eps;
    try
    {
      eps = _material.strain_at_stress(stress.subspan(p * nv, nv), states);
    }
    catch (const std::exception& e)
    {
      throw std::domain_error("point " + std::to_string(p) + ": " + e.what());
    }
    std::copy(eps.begin(), eps.end(), strain.begin() + static_cast<std::ptrdiff_t>(p * nv));
  }
  _trial = _converged;
}

std::vector<SetState> ContinuumPoints::set_states(std::size_t set, bool converged) const
{
  if (set >= _material.num_sets())
    throw std::invalid_argument("ContinuumPoints::set_states: set " + std::to_string(set)
                                + " of " + std::to_string(_material.num_sets()));
  const auto& all = converged ? _converged : _trial;
  std::vector<SetState> out(_num_points);
  for (std::size_t p = 0; p < _num_points; ++p)
    out[p] = all[p * _material.num_sets() + set];
  return out;
}

} // namespace rockjoint::continuum
