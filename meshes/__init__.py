# SPDX-License-Identifier: MIT
"""rockjoint.meshes: gmsh builders of rock blocks cut by joints, node splitting and the JointedMesh.

Sources live in the repository's meshes/ folder; the build copies them to rockjoint/meshes.
"""
from .builders import BOUNDARY_TAGS, JOINT_TAG_OFFSET, column, jointed_block  # noqa: F401
from .joint_geometry import Joint, joint_set, unit_normal  # noqa: F401
from .jointed_mesh import FORMAT_VERSION, JointedMesh, joint_sets_of  # noqa: F401
from .node_splitting import build_jointed_mesh, split_nodes  # noqa: F401
from .gmsh_model import from_gmsh_model, from_msh_file  # noqa: F401
from .openings import CircularOpening, HorseshoeOpening  # noqa: F401
from .tunnel import (OPENING, OPENING_TAG,  # noqa: F401
                     tunnel_section)
from .slope import FACE, TOE, SlopeGeometry, slope_section  # noqa: F401
