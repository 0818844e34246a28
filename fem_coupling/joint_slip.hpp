#pragma once
/// @file joint_slip.hpp
/// The per-point joint law call of the assembler: response at local jump `jump` from the
/// converged point state, writing the trial state.

#include "joint_behaviour.hpp"
#include "joint_point_state.hpp"

#include <array>

namespace rockjoint::fem
{

/// Local traction, tangent and state at local jump `jump` (gdim components, frame axes
/// (n, t1[, t2]), initial jump included) starting from the point's `converged` state; the
/// updated state goes to `trial`. Never throws (see local_response).
LocalResponse joint_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump, const JointPointState& converged,
                             JointPointState& trial);

} // namespace rockjoint::fem
