"""rockjoint.fem_coupling: DOLFINx side of the joint model (distributed jointed meshes, interface coupling).

    from rockjoint.fem_coupling import JointedRockModel, distribute
"""
from .distributed_mesh import (DistributedJointMesh, JointPairs, distribute,  # noqa: F401
                               pair_vertex_positions)
from .split_joints import split_joints  # noqa: F401

try:  # the joint elements need the compiled _rockjoint_fem_coupling (built with -DROCKJOINT_FEM=ON)
    from .behaviours import joint_behaviours  # noqa: F401
    from .coupling import JointCoupling, JointedNonlinearProblem, supported_dofs  # noqa: F401
    from .interface import JointInterface, QuadratureRule  # noqa: F401
    from .linear_solver import LinearSolveError  # noqa: F401
    from .in_situ import InSituStress  # noqa: F401
    from .loads import Load, Support  # noqa: F401
    from .model import JointedRockModel  # noqa: F401
    from .stages import JointedProblem, Stage, StageResult  # noqa: F401
    from .newton import ConvergenceError, NewtonOptions  # noqa: F401
    # The per-point joint behaviour lives in rockjoint.joint (no FE stack); here for FE users too.
    from ..joint import (JointBehaviour, JointPointState, JointStrength, ShearModel,  # noqa: F401
                         ShearState, StrengthModel, barton_bandis_shear_stiffness,
                         closure_at_normal_stress, joint_response, make_strength)
except ImportError as _error:  # pragma: no cover
    if "_rockjoint_fem_coupling" not in str(_error):
        raise
