# SPDX-License-Identifier: MIT
"""A rock slope with one daylighting joint and a tension crack (tests/python/test_fem_slope_*.py):
the plane failure of Hoek & Bray (rockjoint.reference.PlaneFailure) as a jointed FE model whose
factor of safety is found by strength reduction (rockjoint.fem.mechanics.strength_reduction).

H = 30 m face at 60°, a plane at 35° through the toe, a vertical crack 6 m behind the crest;
granite-like blocks (E = 10 GPa, ν = 0.25, ρ = 2650 kg/m³) under gravity; the plane a stiff
Barton-Bandis joint (K_ni = 10 GPa/m: elastic closures of a few mm at most) with the Coulomb
strength under test; the crack with no strength and no residual stiffness (it opens: the LE
block's back is free). Nothing else holds the block: where the plane cannot, the system has no
equilibrium (the mechanism is singular), which is the failure the search looks for."""
import math

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
from rockjoint.fem.mechanics.strength_reduction import reduced_strength
from rockjoint.fem.water.joint_pressure import set_joint_pressure
from rockjoint.joint import JointStrength, StrengthModel
from rockjoint.meshes.slope import SlopeGeometry, slope_section
from rockjoint.reference import PlaneFailure

H, FACE, PLANE, CRACK_BEHIND = 30.0, 60.0, 35.0, 6.0
DENSITY, G = 2650.0, 9.80665
GEOMETRY = SlopeGeometry(height=H, face_angle=FACE, base=15.0, toe_distance=20.0, crest_distance=30.0)
REFERENCE = PlaneFailure(H, FACE, PLANE, CRACK_BEHIND, DENSITY * G, water_unit_weight=998.2 * G)
CRACK_X = GEOMETRY.crest[0] + CRACK_BEHIND


#: the supports of a slope section (2D) and of its extrusion (3D: the strike y held at front and back)
SUPPORTS = {2: (("bottom", "x"), ("bottom", "y"), ("left", "x"), ("right", "x")),
            3: (("bottom", "x"), ("bottom", "y"), ("bottom", "z"), ("left", "x"), ("right", "x"), ("front", "y"),
                ("back", "y"))}


def slope_mesh(mesh_size=3.0, joint_mesh_size=1.0, comm=MPI.COMM_WORLD, length=None):
    """The plane failure slope meshed (length: extruded by `length` [m] along the strike, 3D)."""
    return distribute(slope_section(GEOMETRY, plane_failure_joints(), mesh_size=mesh_size,
                                    joint_mesh_size=joint_mesh_size, length=length, comm=comm), comm)


def block_at(point, mesh_size=3.0, joint_mesh_size=1.0) -> str:
    """The name of the block of slope_mesh's mesh whose cells hold `point` (the serial mesh: the
    block names are the same on every partition)."""
    jm = slope_section(GEOMETRY, plane_failure_joints(), mesh_size=mesh_size, joint_mesh_size=joint_mesh_size)
    x = jm.points[jm.cells]                                    # (cells, 3, 2)
    a, b, c = x[:, 0], x[:, 1], x[:, 2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    u = ((point[0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (point[1] - a[:, 1])) / det
    v = ((b[:, 0] - a[:, 0]) * (point[1] - a[:, 1]) - (point[0] - a[:, 0]) * (b[:, 1] - a[:, 1])) / det
    inside = np.flatnonzero((u >= 0) & (v >= 0) & (u + v <= 1))
    return jm.names["blocks"][int(jm.cell_blocks[inside[0]])]


def plane_failure_joints():
    """The plane through the toe and the tension crack behind the crest, each ending on the other."""
    top = GEOMETRY.base + H
    plane = meshes.Joint(point=GEOMETRY.toe, dip=PLANE, dip_direction=270.0, name="plane", bounded_by=("crack",))
    crack = meshes.Joint(point=(CRACK_X, top - 0.5), dip=90.0, dip_direction=90.0, name="crack", bounded_by=("plane",))
    return [plane, crack]


def crack_foot_y() -> float:
    return GEOMETRY.base + (CRACK_X - GEOMETRY.toe[0]) * math.tan(math.radians(PLANE))


def water(x, depth):
    """p [Pa] at joint points x (gdim, n; the last coordinate up): z_w = `depth` of water in the
    crack (hydrostatic), on the plane falling linearly from the crack's foot to 0 at the toe (Hoek &
    Bray's assumption)."""
    rg = 998.2 * G
    on_crack = np.abs(x[0] - CRACK_X) < 1e-6
    level = crack_foot_y() + depth
    along = np.clip((x[0] - GEOMETRY.toe[0]) / (CRACK_X - GEOMETRY.toe[0]), 0.0, 1.0)
    return np.where(on_crack, rg * np.maximum(level - x[-1], 0.0), rg * depth * along)


def trial_solver(dmesh, friction_angle, cohesion, water_depth=0.0):
    """trial(F): the plane failure slope with the plane's strength reduced by F, solved under
    gravity (and the water)."""
    plane = JointStrength(StrengthModel.coulomb, friction_angle=friction_angle, cohesion=cohesion)
    pressure = (lambda x: water(x, water_depth)) if water_depth > 0.0 else None
    return slope_trials(dmesh, {"plane": plane}, pressure)


def slope_trials(dmesh, strengths: dict, pressure=None):
    """trial(F): the slope of `dmesh` with every joint's strength ({joint: JointStrength}; a joint
    not named: the crack, no strength) reduced by F, solved under gravity and then the water
    `pressure` (a callable of the joint points, or None); raises ConvergenceError /
    LinearSolveError where there is no equilibrium."""
    law = rockjoint.BartonBandis(1e10, 5e-3)
    gdim = dmesh.mesh.geometry.dim
    free = JointStrength(StrengthModel.coulomb, friction_angle=0.0, cohesion=0.0)
    joints = list(dmesh.names["joints"].values())

    def trial(factor):
        model = JointedRockModel(dmesh, rock=(10e9, 0.25), joints={j: law for j in joints},
                                 shear_stiffness=1e9, density=DENSITY,
                                 strength={j: reduced_strength(strengths.get(j, free), factor) for j in joints},
                                 plane="strain" if gdim == 2 else None, linear_solver="direct",
                                 newton=NewtonOptions(verbose=False, max_iterations=40))
        for side, component in SUPPORTS[gdim]:
            model.fix(side, component)
        model.solve(load_steps=2, name="gravity")
        if pressure is not None:
            set_joint_pressure(model, pressure)
            model.solve(load_steps=2, name="water")
        return model
    return trial
