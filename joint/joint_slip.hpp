// SPDX-License-Identifier: MIT
#pragma once
/// @file joint_slip.hpp
/// Path-dependent joint response: Coulomb (or Barton) slip with a non-associated dilatancy and
/// a tension cut-off, integrated by backward Euler from the converged point state
/// (docs/joint-strength.md). The result depends only on (converged state, current jump), so
/// every Newton iteration of a load step recomputes its trial state from the same start.

#include "joint_behaviour.hpp"
#include "joint_point_state.hpp"

#include <array>

namespace rockjoint::joint
{

/// Traction, consistent tangent and trial state at local jump `jump` (gdim components:
/// normal, t1[, t2]) from the `converged` state of the point.
///
/// Elastic predictor τ_tr = k_s (j_s - s_n) at the converged dilation; if f = |τ_tr| - τ_y(σ_n)
/// > 0 the slip increment Δλ solves τ_y(σ_n(Δ_e)) = k_s (|j_s - s_n| - Δλ) with
/// Δ_e = -j_n + d_n + tan ψ Δλ (radial return: the slip follows the trial shear direction,
/// in 3D a circular cone in (τ1, τ2)), and the tangent is the consistent one (unsymmetric
/// with friction: the shear strength follows the normal stress). An open joint carries the
/// residual spring only and its slip is frozen; so does a joint in contact whose strength has
/// fallen below that spring's traction k_r |j_s - s_n| (the residual floor, while slip does not
/// dilate), which makes the shear traction continuous at opening. Never throws: a non-finite traction (a
/// closure past the law's maximum) marks a failed trial; status/shear_state report the
/// point's state.
///
/// `pore_pressure` p [Pa] of the water in the joint (default 0: dry): everything above sees
/// the effective stress (the law's σ is σ'_n), and the normal traction carries the water's push
/// α p on top (joint_behaviour.hpp); LocalResponse::normal_stress stays the law's σ'_n.
LocalResponse joint_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump,
                             const JointPointState& converged, JointPointState& trial,
                             double pore_pressure = 0.0);

/// Response at local jump `jump` (gdim components) from the virgin state (no slip, no
/// dilation): joint_response() with a default JointPointState. Never throws; past the law's
/// maximum closure the traction is infinite (status beyond_maximum_closure), which the Newton
/// solver treats as a failed trial.
LocalResponse local_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump);

} // namespace rockjoint::joint
