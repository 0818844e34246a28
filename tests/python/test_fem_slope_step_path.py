# SPDX-License-Identifier: MIT
"""A step path of two joint sets against the limit equilibrium of its block (issue 40, item 4):
the slope of slope_cases.py failing along three segments of a set dipping 35° out of the face,
joined by two vertical steps of a second set, and cut off by a tension crack. The block can only
translate down the 35° segments, which opens the steps and the crack (they carry nothing), so its
limit equilibrium is the plane failure's with the segments' length and the block's own weight::

    F = (c Σ A_i + W cos ψ tan φ) / (W sin ψ),

W = γ × the block's area (the shoelace formula on its outline: toe, the path, the crack, the crest).
An independent computation from the geometry; the FE factor of safety by strength reduction must
be within 3 % of it."""
import math

import numpy as np
import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from slope_cases import DENSITY, G, GEOMETRY, slope_trials  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import distribute  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402
from rockjoint.joint import JointStrength, StrengthModel  # noqa: E402
from rockjoint.meshes.slope import slope_section  # noqa: E402

PSI = 35.0
STEPS = (30.0, 42.0)      # x of the vertical steps [m]
RISE = 3.0                # height of each step [m]
CRACK_X = 48.0


def path_points():
    """The step path's corners from the toe to the crack's foot."""
    t = math.tan(math.radians(PSI))
    pts = [GEOMETRY.toe]
    for x in (*STEPS, CRACK_X):
        x0, y0 = pts[-1]
        pts.append((x, y0 + (x - x0) * t))
        if x != CRACK_X:
            pts.append((x, pts[-1][1] + RISE))
    return pts


def step_path_joints():
    p = path_points()
    mid = lambda a, b: tuple(0.5 * (np.asarray(a) + np.asarray(b)))  # noqa: E731
    a = lambda k, bounds: meshes.Joint(point=mid(p[2 * k], p[2 * k + 1]), dip=PSI, dip_direction=270.0,  # noqa: E731
                                       name=f"segment_{k + 1}", bounded_by=bounds, joint_set="segments")
    b = lambda k, bounds: meshes.Joint(point=mid(p[2 * k + 1], p[2 * k + 2]), dip=90.0, dip_direction=90.0,  # noqa: E731
                                       name=f"step_{k + 1}", bounded_by=bounds, joint_set="steps")
    top = GEOMETRY.base + GEOMETRY.height
    return [a(0, ("step_1",)), b(0, ("segment_1", "segment_2")), a(1, ("step_1", "step_2")),
            b(1, ("segment_2", "segment_3")), a(2, ("step_2", "crack")),
            meshes.Joint(point=(CRACK_X, top - 0.5), dip=90.0, dip_direction=90.0, name="crack",
                         bounded_by=("segment_3",))]


def limit_equilibrium(phi, c):
    p = path_points()
    top = GEOMETRY.base + GEOMETRY.height
    outline = [*p, (CRACK_X, top), GEOMETRY.crest]
    area = 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(outline, outline[1:] + outline[:1])))
    w = DENSITY * G * area
    psi = math.radians(PSI)
    segments = sum(math.dist(p[2 * k], p[2 * k + 1]) for k in range(3))
    return (c * segments + w * math.cos(psi) * math.tan(phi)) / (w * math.sin(psi))


@pytest.mark.parametrize("phi_deg, cohesion", [(40.0, 0.0), (30.0, 40e3)])
def test_a_step_path_fails_as_its_block_in_limit_equilibrium(phi_deg, cohesion):
    phi = math.radians(phi_deg)
    strength = JointStrength(StrengthModel.coulomb, friction_angle=phi, cohesion=cohesion)
    joints = step_path_joints()
    dmesh = distribute(slope_section(GEOMETRY, joints, mesh_size=3.0, joint_mesh_size=0.75, comm=MPI.COMM_WORLD),
                       MPI.COMM_WORLD)
    strengths = {j.name: strength for j in joints if j.name != "crack"}
    found = factor_of_safety(slope_trials(dmesh, strengths), tolerance=0.005)
    expected = limit_equilibrium(phi, cohesion)
    print(f"step path, φ = {phi_deg}°, c = {cohesion * 1e-3:g} kPa: F = {found.factor:.4f} "
          f"({len(found.trials)} trials), LE {expected:.4f}, {100 * (found.factor / expected - 1):+.2f} %")
    assert found.bounded
    assert found.factor == pytest.approx(expected, rel=0.03)
