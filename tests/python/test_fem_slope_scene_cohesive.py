# SPDX-License-Identifier: MIT
"""A cohesive plane failure as a slope scene (`rockjoint run`), 2D and extruded 3D, against Hoek &
Bray's limit equilibrium (rockjoint.reference.PlaneFailure, the block's weight from its own
geometry): H = 30 m at 60°, a persistent plane at 35° through the toe, a free crack 6 m behind the
crest ending on it; c = 60 kPa, φ = 30°, T = 100 kPa (below the Coulomb apex c / tan φ: without it
the plane's tip on the ground cycles, docs/slopes.md "Mesh dependence").

What it guards: a factor-of-safety search finds a mechanism by its singular system, so the joints'
tables must carry nothing open (k_res = 0, scenes/joint_laws.py). With the tables' default opening
stiffness the freed block was held at a large displacement and the scene's F came out 1.371
against 1.284. The 3D scene (its section extruded 3 m, fixed front and back) gives the 2D F."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from rockjoint.reference import PlaneFailure  # noqa: E402
from rockjoint.scenes import load_scene, make_plan, run_scene  # noqa: E402
from scene_cases import write  # noqa: E402

TOE_PLANE_Z = 15.0 + 20.0 * math.tan(math.radians(35.0))   # the plane through the toe (20, 15) at x = 40 m
SCENE = f"""\
name: cohesive_plane
geometry:
  kind: slope
  height: 30 m
  face_angle: 60 deg
  base: 15 m
  toe_distance: 20 m
  crest_distance: 30 m
  joint_sets:
    - {{name: plane, point: [40 m, {TOE_PLANE_Z!r} m], dip: 35 deg, dip_direction: 270 deg, spacing: 6 m, count: 1}}
  tension_crack: {{behind_crest: 6 m, ends_on: plane}}
rock: {{young: 10 GPa, poisson: 0.25, density: 2650 kg/m3}}
joints:
  plane:
    law: {{model: barton_bandis, parameters: {{initial_normal_stiffness: 10 MPa/mm, maximum_closure: 5 mm}}}}
    strength: {{model: coulomb, friction_angle: 30 deg, cohesion: 60 kPa, tensile_strength: 100 kPa}}
  tension_crack:
    law: {{model: barton_bandis, parameters: {{initial_normal_stiffness: 10 MPa/mm, maximum_closure: 5 mm}}}}
supports: {{bottom: all, left: x, right: x}}
stages:
  - {{name: weight, steps: 2}}
error_budget: 10 %
mesh: {{size: 3 m, joint_size: 1.5 m}}
factor_of_safety: {{tolerance: 1 %}}
"""
REFERENCE = PlaneFailure(30.0, 60.0, 35.0, 6.0, 2650.0 * 9.80665)


def extruded(text: str) -> str:
    return (text.replace("  joint_sets:", "  length: 3 m\n  joint_sets:")
                .replace("point: [40 m, ", "point: [40 m, 1.5 m, ")
                .replace("right: x}", "right: x, front: y, back: y}"))


def factor(tmp_path, text):
    scene = load_scene(write(tmp_path, text))
    return run_scene(scene, make_plan(scene), str(tmp_path / "out"), MPI.COMM_WORLD).safety.found


def test_cohesive_plane_failure_scene_matches_limit_equilibrium_in_2d_and_3d(tmp_path):
    expected = REFERENCE.factor_of_safety(math.radians(30.0), 60e3)
    flat = factor(tmp_path, SCENE)
    solid = factor(tmp_path, extruded(SCENE))
    print(f"cohesive plane failure scene: F = {flat.factor:.4f} (2D), {solid.factor:.4f} (3D), LE {expected:.4f}")
    for found in (flat, solid):
        assert found.decided_by_strength
        assert found.factor == pytest.approx(expected, rel=0.03)
    assert solid.factor == pytest.approx(flat.factor, rel=0.01)
    assert flat.moving and solid.moving


def test_a_3d_slope_set_runs_along_the_strike(tmp_path):
    from rockjoint.scenes import SceneError
    bad = extruded(SCENE).replace("dip_direction: 270 deg", "dip_direction: 180 deg")
    with pytest.raises(SceneError, match="in a 3D slope a joint set runs along y"):
        load_scene(write(tmp_path, bad))


def wet(text: str) -> str:
    """The scene with its water computed: the ground saturated (head 45 m on the top, p = 0 there),
    the face and the toe drained; the crack far more open (50 mm) than the plane (10 mm), both wide
    against their closures, so the crack stands full and the plane's water falls linearly to the
    toe: Hoek & Bray's 'crack full' distribution, from the flow."""
    flow = {"plane": "10 mm", "tension_crack": "50 mm"}
    for name, aperture in flow.items():
        law = "law: {model: barton_bandis, parameters: {initial_normal_stiffness: 10 MPa/mm, maximum_closure: 5 mm}}"
        text = text.replace(f"  {name}:\n    {law}", f"  {name}:\n    {law}\n    flow: {{law: cubic_law, "
                            f"initial_aperture: {aperture}}}", 1)
    return text.replace("error_budget:", "water: {heads: {top: 45 m}, pressures: {face: 0 MPa, toe: 0 MPa}, "
                                         "coupling: two_way}\nerror_budget:")


def test_the_slopes_coupled_water_gives_the_full_crack_of_limit_equilibrium(tmp_path):
    expected = PlaneFailure(30.0, 60.0, 35.0, 6.0, 2650.0 * 9.80665, water_unit_weight=998.2 * 9.80665)
    expected = expected.factor_of_safety(math.radians(30.0), 60e3, expected.crack_depth)
    text = wet(SCENE)
    assert text.count("cubic_law") == 2 and "two_way" in text
    found = factor(tmp_path, text)
    print(f"cohesive plane failure with its coupled water: F = {found.factor:.4f}, LE (crack full) {expected:.4f}")
    assert found.decided_by_strength
    assert found.factor == pytest.approx(expected, rel=0.03)
