// SPDX-License-Identifier: MIT
#pragma once
/// @file continuum_points.hpp
/// The equivalent-continuum material over many points (the quadrature points of the smeared
/// cells): converged and trial set states per point, MGIS style. evaluate() computes the trial
/// state from the converged one at every call; commit() accepts it after a converged load step,
/// revert() drops it after a failed one.

#include "equivalent_continuum.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace rockjoint::continuum
{

/// An EquivalentContinuum material at n points, with converged and trial joint-set states per
/// point (MGIS style: evaluate(), commit(), revert()).
class ContinuumPoints
{
public:
  /// `num_points` points of `material`, every set state at rest (zero jump and slip).
  ContinuumPoints(EquivalentContinuum material, std::size_t num_points);

  /// The material every point shares.
  const EquivalentContinuum& material() const { return _material; }
  /// Number of points n.
  std::size_t num_points() const { return _num_points; }

  /// Stress (n × strain_size()) and tangent (n × strain_size()²) at the total strains `strain`
  /// (n × strain_size()); returns the number of points whose local solve failed (NaN stress).
  std::size_t evaluate(std::span<const double> strain, std::span<double> stress,
                       std::span<double> tangent);
  /// Accept the trial states (after a converged load step).
  void commit() { _converged = _trial; }
  /// Drop the trial states (after a failed load step).
  void revert() { _trial = _converged; }

  /// Start from the stresses `stress` (n × strain_size()): the set states carrying them become
  /// the converged state and the matching strains (n × strain_size()) are written to `strain`
  /// (EquivalentContinuum::strain_at_stress per point; its errors name the point).
  void initialise_from_stress(std::span<const double> stress, std::span<double> strain);

  /// States of set `set` at every point (converged if `converged`, else trial).
  std::vector<SetState> set_states(std::size_t set, bool converged) const;

private:
  EquivalentContinuum _material;
  std::size_t _num_points;
  std::vector<SetState> _converged, _trial; // point major: [point][set]
};

} // namespace rockjoint::continuum
