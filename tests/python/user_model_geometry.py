# SPDX-License-Identifier: MIT
"""The geometry of a user's own model for the tests: a square (cube) cut by a joint dipping 30°
through its centre, built in gmsh by hand (not by a rockjoint builder) with physical groups
blocks 'lower'/'upper', joint 'fault', boundaries bottom/top/left/right[/front/back].
"""
import math

import numpy as np

SIZE = 2.0                                     # square / cube edge [m]
DIP = math.radians(30.0)                       # joint dip (rises toward +x)


def joint_height(x):
    return 0.5 * SIZE + (x - 0.5 * SIZE) * math.tan(DIP)


def build_gmsh_model(gmsh, dim, mesh_size, order=1, name_joint=True):
    """The user's geometry in the current gmsh session (blocks 'lower'/'upper', joint 'fault',
    boundaries bottom/top/left/right[/front/back]); meshed unless mesh_size is None."""
    gmsh.model.add(f"user_case_{dim}d")
    occ = gmsh.model.occ
    z0, z1 = joint_height(0.0), joint_height(SIZE)
    if dim == 2:
        body = occ.addRectangle(0, 0, 0, SIZE, SIZE)
        cut = occ.addLine(occ.addPoint(0, z0, 0), occ.addPoint(SIZE, z1, 0))
    else:
        body = occ.addBox(0, 0, 0, SIZE, SIZE, SIZE)
        corners = [occ.addPoint(0, 0, z0), occ.addPoint(SIZE, 0, z1), occ.addPoint(SIZE, SIZE, z1),
                   occ.addPoint(0, SIZE, z0)]
        loop = occ.addCurveLoop([occ.addLine(corners[i], corners[(i + 1) % 4]) for i in range(4)])
        cut = occ.addPlaneSurface([loop])
    _, pieces = occ.fragment([(dim, body)], [(dim - 1, cut)])
    occ.synchronize()
    for name, above in (("lower", False), ("upper", True)):
        ents = [t for _, t in gmsh.model.getEntities(dim)
                if (occ.getCenterOfMass(dim, t)[dim - 1] > joint_height(occ.getCenterOfMass(dim, t)[0])) == above]
        gmsh.model.setPhysicalName(dim, gmsh.model.addPhysicalGroup(dim, ents), name)
    if name_joint:
        gmsh.model.setPhysicalName(dim - 1, gmsh.model.addPhysicalGroup(dim - 1, [t for _, t in pieces[1]]),
                                   "fault")
    sides = [("left", "right"), ("bottom", "top")] if dim == 2 else \
        [("left", "right"), ("front", "back"), ("bottom", "top")]
    groups = {}
    outer = gmsh.model.getBoundary(gmsh.model.getEntities(dim), combined=True, oriented=False)
    for _, f in outer:
        lo, hi = np.array(gmsh.model.getBoundingBox(dim - 1, abs(f))).reshape(2, 3)
        for axis in range(dim):
            for end, value in enumerate((0.0, SIZE)):
                if hi[axis] - lo[axis] < 1e-6 and abs(lo[axis] - value) < 1e-6:
                    groups.setdefault(sides[axis][end], []).append(abs(f))
    for name, ents in groups.items():
        gmsh.model.setPhysicalName(dim - 1, gmsh.model.addPhysicalGroup(dim - 1, ents), name)
    if mesh_size is not None:
        gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size)
        gmsh.option.setNumber("Mesh.ElementOrder", order)
        gmsh.model.mesh.generate(dim)
