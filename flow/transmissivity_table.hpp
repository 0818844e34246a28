// SPDX-License-Identifier: MIT
#pragma once
/// @file transmissivity_table.hpp
/// A joint's transmissivity as a function of its normal closure, T(Δ), tabulated from the
/// (Δ_i, T_i) of the same walls' contact and flow solutions at a sequence of loads
/// (docs/flow.md). T follows the closure only: a law with history gives Δ on its unloading
/// and reloading branches, and T(Δ) follows it there.
///
/// Between the knots: the monotone C¹ Hermite interpolant of the project
/// (constitutive/monotone_hermite.hpp, PCHIP data slopes) in -ln T, because T falls by orders
/// of magnitude over a closure curve (a cubic in T itself would undershoot to negative values
/// between widely spaced knots) and ln T is nearly linear in Δ once the contact spots grow.
/// Below the first knot (the walls opened past it): rigid separation, e_h grows by the opening,
/// T = (e_h(Δ_0) + Δ_0 - Δ)³/12. Beyond the last positive knot: ln T continued with its end
/// slope (exponential decay); if a later knot has T = 0 (no open path left), T falls linearly
/// to 0 at the first such knot and stays 0.

#include <rockjoint/constitutive/monotone_hermite.hpp>

#include <limits>
#include <span>
#include <vector>

namespace rockjoint::flow
{

/// A joint's transmissivity T(Δ) [m³] as a function of its normal closure Δ [m], tabulated
/// from contact and flow solutions (file comment: the interpolant and its extensions).
class TransmissivityTable
{
public:
  /// @param closure Δ_i [m], finite and strictly increasing (n >= 2)
  /// @param transmissivity T_i [m³], finite, >= 0 and non-increasing, T_0 > 0
  /// Throws std::invalid_argument naming the offending knot.
  TransmissivityTable(std::span<const double> closure, std::span<const double> transmissivity);

  /// T [m³] at closure Δ [m] (NaN for NaN).
  double transmissivity(double closure) const;
  /// Batch: out[i] = T(closure[i]); sizes equal.
  void transmissivity(std::span<const double> closure, std::span<double> out) const;

  /// Knots Δ_i [m].
  const std::vector<double>& closures() const { return _closure; }
  /// T_i [m³] at the knots.
  const std::vector<double>& transmissivities() const { return _transmissivity; }

private:
  std::vector<double> _closure, _transmissivity; // the knots as given
  std::size_t _positive = 0;                      // knots with T > 0 (the first ones)
  std::vector<constitutive::hermite::Segment> _segments; // -ln T on the positive knots
  double _end_slope = 0.0; // d(-ln T)/dΔ at the last positive knot [1/m]
};

} // namespace rockjoint::flow
