# SPDX-License-Identifier: MIT
"""rockjoint.fem: the finite-element rock-mass model in DOLFINx, by part: mesh (distributed jointed
meshes), mechanics (blocks, joint elements, stages, the model), water (flow along the joints, Darcy),
solvers (Newton, SNES, linear), output (XDMF, pictures, monitors).

    from rockjoint.fem import JointedRockModel, distribute
"""
from importlib.util import find_spec

from .._fe_required import fe_required
from .mesh.distributed_mesh import (DistributedJointMesh, JointPairs, distribute,  # noqa: F401
                               pair_vertex_positions)
from .mesh.split_joints import split_joints  # noqa: F401
from ..joint import joint_behaviours  # noqa: F401  (no FE stack; here for FE users too)

# The joint elements need the compiled _rockjoint_fem_coupling (built with -DROCKJOINT_FEM=ON).
# Only a build without that file leaves them out, and only outside CI / ROCKJOINT_REQUIRE_FE=1:
# an extension that exists but fails to load (undefined symbol, ABI mismatch) raises its own
# ImportError here instead of silently removing JointedRockModel and friends.
_HAS_FE = find_spec("rockjoint._rockjoint_fem_coupling") is not None
if _HAS_FE or fe_required():
    from .mechanics.coupling import JointCoupling, supported_dofs  # noqa: F401
    from .mechanics.nonlinear_problem import JointedNonlinearProblem, NewtonSolverError  # noqa: F401
    from .mechanics.law_range import BeyondRangeError, JointSummary, RangeWarning, Status  # noqa: F401
    from .water.darcy import DarcyFlow, darcy_flow, equivalent_permeability  # noqa: F401
    from .water.joint_flow import Fluid, NetworkFlow, network_flow  # noqa: F401
    from .mechanics.interface import JointInterface, QuadratureRule  # noqa: F401
    from .solvers.linear_solver import LinearSolveError  # noqa: F401
    from .mechanics.in_situ import InSituStress  # noqa: F401
    from .mechanics.loads import Load, Support  # noqa: F401
    from .mechanics.model import JointedRockModel  # noqa: F401
    from .mechanics.problem import JointedProblem  # noqa: F401
    from .mechanics.stages import Stage, StageResult  # noqa: F401
    from .solvers.newton import ConvergenceError, NewtonOptions  # noqa: F401
    # The per-point joint behaviour lives in rockjoint.joint (no FE stack); here for FE users too.
    from ..joint import (JointBehaviour, JointPointState, JointStrength, ShearModel,  # noqa: F401
                         ShearState, StrengthModel, barton_bandis_shear_stiffness,
                         closure_at_normal_stress, joint_response, make_strength)
else:
    _FE_NAMES = {"JointCoupling", "JointedNonlinearProblem", "NewtonSolverError", "supported_dofs",
                 "BeyondRangeError", "JointSummary", "RangeWarning", "Status",
                 "JointInterface", "QuadratureRule", "LinearSolveError", "InSituStress", "Load",
                 "Support", "JointedRockModel", "JointedProblem", "Stage", "StageResult",
                 "ConvergenceError", "NewtonOptions", "DarcyFlow", "darcy_flow",
                 "equivalent_permeability", "Fluid", "NetworkFlow", "network_flow"}

    def __getattr__(name):
        if name in _FE_NAMES:
            raise AttributeError(f"rockjoint.fem.{name} needs the compiled extension "
                                 f"rockjoint._rockjoint_fem_coupling, which this build lacks "
                                 f"(configure with -DROCKJOINT_FEM=ON)")
        raise AttributeError(f"module 'rockjoint.fem' has no attribute {name!r}")
