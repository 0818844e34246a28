// SPDX-License-Identifier: MIT
#pragma once
/// @file joint_point_state.hpp
/// Path-dependent state of one joint quadrature point (MGIS style: the assembler keeps a
/// converged and a trial copy per point; every evaluation computes the trial state from the
/// converged one, commit_state() accepts it after a converged load step).

#include <array>

namespace rockjoint::joint
{

/// Path-dependent state of one joint quadrature point (converged or trial copy).
struct JointPointState
{
  std::array<double, 2> slip{};  ///< irreversible shear displacement along t1, t2 [m]
  double dilation = 0.0;         ///< normal opening produced by slip (dilatancy) [m]
  double accumulated_slip = 0.0; ///< path length of the slip, ∫|d slip| [m]
  bool bond_broken = false;      ///< tensile strength exceeded once: bond (c, T) lost for good
  /// Largest elastic closure Δ_e reached in a converged state, Δ_m [m], for every closure law:
  /// a law with history (NormalHysteresis) unloads on branches set by it, and a transmissivity
  /// law with history reads it (docs/flow.md). Starts at the in-situ pre-closure; the trial copy
  /// follows every evaluation, so Δ_m grows only when a converged load step is committed.
  double maximum_closure = 0.0;
};

} // namespace rockjoint::joint
