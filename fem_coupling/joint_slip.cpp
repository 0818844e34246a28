#include "joint_slip.hpp"

namespace rockjoint::fem
{

LocalResponse joint_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump, const JointPointState& converged,
                             JointPointState& trial)
{
  // Elastic joint (no slip yet): the state does not evolve.
  trial = converged;
  return local_response(behaviour, gdim, jump);
}

} // namespace rockjoint::fem
