# SPDX-License-Identifier: MIT
"""Benched slopes (meshes.slope.SlopeGeometry(benches=...), issue 40 item 1): the outline of a face
broken by horizontal benches (closed forms of its lengths and area, written out here), bad benches
named, and the plane failure of a benched slope by strength reduction against its limit
equilibrium, the block's weight by the shoelace formula on corners computed here by hand."""
import math

import numpy as np
import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import distribute  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402
from rockjoint.joint import JointStrength, StrengthModel  # noqa: E402
from rockjoint.meshes.slope import SlopeGeometry, slope_section  # noqa: E402
from slope_cases import DENSITY, G, slope_trials  # noqa: E402
from test_slope_mesh import group_length  # noqa: E402

H, FACE, BENCH_AT, BENCH_WIDTH, PLANE, CRACK_BEHIND = 30.0, 65.0, 15.0, 4.0, 35.0, 6.0
GEOMETRY = SlopeGeometry(height=H, face_angle=FACE, base=15.0, toe_distance=20.0, crest_distance=30.0,
                         benches=((BENCH_AT, BENCH_WIDTH),))
RUN = BENCH_AT / math.tan(math.radians(FACE))          # each of the two faces rises 15 m at 65°
TOE = (20.0, 15.0)
CORNERS = [TOE, (20.0 + RUN, 30.0), (20.0 + RUN + BENCH_WIDTH, 30.0), (20.0 + 2 * RUN + BENCH_WIDTH, 45.0)]
CRACK_X = CORNERS[-1][0] + CRACK_BEHIND


def shoelace(points) -> float:
    return 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1])))


def test_the_benched_outline_has_the_geometry_of_the_slope():
    jm = slope_section(GEOMETRY, [], mesh_size=3.0)
    assert GEOMETRY.crest == pytest.approx(CORNERS[-1], abs=1e-12)
    face = 2 * BENCH_AT / math.sin(math.radians(FACE)) + BENCH_WIDTH
    width = CORNERS[-1][0] + 30.0
    expected = {"bottom": width, "right": 45.0, "top": 30.0, "face": face, "toe": 20.0, "left": 15.0}
    for name, length in expected.items():
        assert group_length(jm, name) == pytest.approx(length, rel=1e-12), name
    a, b = (jm.points[jm.cells[:, k]] - jm.points[jm.cells[:, 0]] for k in (1, 2))
    area = 0.5 * np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]).sum()
    outline = [(0.0, 0.0), (width, 0.0), (width, 45.0), *CORNERS[::-1], (0.0, 15.0)]
    assert area == pytest.approx(shoelace(outline), rel=1e-12)


def test_bad_benches_are_refused_by_name():
    base = dict(height=30.0, face_angle=60.0, base=15.0, toe_distance=20.0, crest_distance=30.0)
    for benches, words in ((((0.0, 3.0),), "bench 1: elevation"), (((30.0, 3.0),), "bench 1: elevation"),
                           (((10.0, 3.0), (8.0, 3.0)), "bench 2: elevation"), (((10.0, -1.0),), "bench 1 width")):
        with pytest.raises(ValueError, match=words):
            SlopeGeometry(**base, benches=benches)


def plane_failure():
    """The plane through the toe at 35°, ended by a vertical crack 6 m behind the crest."""
    plane = meshes.Joint(point=TOE, dip=PLANE, dip_direction=270.0, name="plane", bounded_by=("crack",))
    crack = meshes.Joint(point=(CRACK_X, 44.0), dip=90.0, dip_direction=90.0, name="crack", bounded_by=("plane",))
    return [plane, crack]


def limit_equilibrium(phi: float, cohesion: float) -> float:
    """F = (c A + W cos ψ tan φ) / (W sin ψ): the block toe, the face's corners, the crest, the
    crack's top and foot."""
    psi = math.radians(PLANE)
    foot = (CRACK_X, TOE[1] + (CRACK_X - TOE[0]) * math.tan(psi))
    weight = DENSITY * G * shoelace([*CORNERS, (CRACK_X, 45.0), foot])
    length = (CRACK_X - TOE[0]) / math.cos(psi)
    return (cohesion * length + weight * math.cos(psi) * math.tan(phi)) / (weight * math.sin(psi))


def test_plane_failure_of_a_benched_slope_matches_limit_equilibrium():
    phi, c = math.radians(30.0), 60e3
    dmesh = distribute(slope_section(GEOMETRY, plane_failure(), mesh_size=3.0, joint_mesh_size=1.0,
                                     comm=MPI.COMM_WORLD), MPI.COMM_WORLD)
    strength = JointStrength(StrengthModel.coulomb, friction_angle=phi, cohesion=c)
    found = factor_of_safety(slope_trials(dmesh, {"plane": strength}), tolerance=0.005)
    expected = limit_equilibrium(phi, c)
    print(f"benched plane failure: F = {found.factor:.4f} (bracket {found.stable:.4f}-{found.failed:.4f}), "
          f"LE {expected:.4f}, {100 * (found.factor / expected - 1):+.2f} %")
    assert found.decided_by_strength
    assert found.factor == pytest.approx(expected, rel=0.03)
