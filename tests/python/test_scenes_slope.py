# SPDX-License-Identifier: MIT
"""The `slope` scene kind (docs/slopes.md, "Slope scenes"): its keys checked whole (bad geometry
named by its key and line), and the planner's cost of a factor-of-safety search in trial solves,
against the count worked out by hand from the search's rule (bracketing x2 from F = 1, then
bisection until the bracket is within the tolerance of its stable end)."""
import pytest

from rockjoint.scenes import SceneError, load_scene, make_plan
from rockjoint.scenes.slope_plan import trial_count
from scene_cases import SCENES, write

SLOPE = """\
name: slope
geometry:
  kind: slope
  height: 30 m
  face_angle: 65 deg
  joint_sets:
    - {name: bedding, point: [40 m, 30 m], dip: 35 deg, dip_direction: 270 deg, spacing: 6 m, count: 2}
  tension_crack: {behind_crest: 8 m, ends_on: bedding}
rock: {young: 20 GPa, poisson: 0.25, density: 2650 kg/m3}
joints:
  bedding:
    law: {model: barton_bandis, parameters: {initial_normal_stiffness: 10 MPa/mm, maximum_closure: 0.5 mm}}
    strength: {model: coulomb, friction_angle: 40 deg}
  tension_crack:
    law: {model: barton_bandis, parameters: {initial_normal_stiffness: 10 MPa/mm, maximum_closure: 0.5 mm}}
supports: {bottom: all, left: x, right: x}
stages:
  - {name: weight}
error_budget: 10 %
mesh: {size: 3 m}
factor_of_safety: {tolerance: 2 %}
"""


def test_a_slope_loads_with_its_defaults_and_a_free_crack(tmp_path):
    scene = load_scene(write(tmp_path, SLOPE))
    g = scene["geometry"]
    assert (g["base"], g["toe_distance"], g["crest_distance"]) == (15.0, 30.0, 30.0)   # H/2, H, H
    assert g["dimension"] == 2
    assert scene["factor_of_safety"] == {"tolerance": pytest.approx(0.02), "largest": 50.0}
    crack = scene.strengths["tension_crack"]          # no strength given: open ground, no friction
    assert crack.friction_angle == 0.0 and crack.cohesion == 0.0


# (what, old text, new text, key path the message names, words of the message)
MALFORMED = [
    ("a bench without its elevation", "  face_angle: 65 deg", "  face_angle: 65 deg\n  benches: [{width: 5 m}]",
     "geometry.benches[0]", "missing key 'elevation'"),
    ("benches out of order", "  face_angle: 65 deg",
     "  face_angle: 65 deg\n  benches: [{elevation: 20 m, width: 4 m}, {elevation: 10 m, width: 4 m}]",
     "geometry.benches[1].elevation", "must lie above the toe and the bench below"),
    ("a bench above the crest", "  face_angle: 65 deg", "  face_angle: 65 deg\n  benches: [{elevation: 30 m, width: 4 m}]",
     "geometry.benches[0].elevation", "below the crest"),
    ("a set that misses the slope", "spacing: 6 m, count: 2}", "spacing: 6 m, count: 9}", "geometry.joint_sets[0]",
     "misses the slope section"),
    ("a point outside", "point: [40 m, 30 m]", "point: [5 m, 30 m]", "geometry.joint_sets[0].point",
     "not inside the slope section"),
    ("a crack on no set", "ends_on: bedding}", "ends_on: cross}", "geometry.tension_crack.ends_on",
     "no joint set 'cross'"),
    ("a crack beyond the section", "behind_crest: 8 m", "behind_crest: 31 m", "geometry.tension_crack.behind_crest",
     "beyond the section"),
    ("no weight", "poisson: 0.25, density: 2650 kg/m3}", "poisson: 0.25}", "rock", "missing key 'density'"),
    ("a uniform in-situ stress", "supports:", "in_situ: {vertical: 1 MPa}\nsupports:", "in_situ",
     "its own weight"),
    ("a table and heads", "error_budget:", "water: {table: 30 m, heads: {top: 45 m}, coupling: two_way}\nerror_budget:",
     "water.table", "either the prescribed table"),
    ("flow one way", "error_budget:", "water: {heads: {top: 45 m}, pressures: {face: 0 MPa}}\nerror_budget:",
     "water.coupling", "must act on its joints: coupling: two_way"),
    ("a slope's key on a block", None, None, "geometry.face_angle", "not used by kind block"),
    ("a tensile strength past the apex", "strength: {model: coulomb, friction_angle: 40 deg}",
     "strength: {model: coulomb, friction_angle: 40 deg, cohesion: 10 kPa, tensile_strength: 1 MPa}",
     "joints.bedding.strength", "the apex of the Coulomb cone"),
    ("a tolerance out of range", "tolerance: 2 %", "tolerance: 80 %", "factor_of_safety.tolerance", "out of range"),
]


@pytest.mark.parametrize("what, old, new, key, words", MALFORMED, ids=[m[0] for m in MALFORMED])
def test_bad_slope_geometry_is_named(tmp_path, what, old, new, key, words):
    if old is None:   # a block given a slope's face angle
        text = SLOPE.replace("kind: slope\n  height: 30 m", "kind: block\n  size: [60 m, 45 m]").replace(
            "  tension_crack: {behind_crest: 8 m, ends_on: bedding}\n", "")
    else:
        assert old in SLOPE
        text = SLOPE.replace(old, new)
    with pytest.raises(SceneError) as err:
        load_scene(write(tmp_path, text))
    assert f": {key}: " in str(err.value) and words in str(err.value), str(err.value)


def test_a_factor_of_safety_is_asked_of_slopes_only(tmp_path):
    text = open(f"{SCENES}/blocky_rock_mass.yaml", encoding="utf-8").read() + "factor_of_safety: {tolerance: 1 %}\n"
    with pytest.raises(SceneError, match="factor_of_safety: the factor of safety is searched for slopes only"):
        load_scene(write(tmp_path, text))


@pytest.mark.parametrize("factor, tolerance, by_hand", [
    # F in [1, 2): trials at 1 (holds) and 2 (fails), then halving the width 1 until <= 0.01 x 1.5: 7 more
    (1.5, 0.01, 2 + 7),
    # F in [0.5, 1): 1 fails, 0.5 holds; width 0.5 down to <= 0.01 x 0.7 = 0.007: 7 halvings (0.0039)
    (0.7, 0.01, 2 + 7),
    # F in [4, 8): 1, 2, 4 hold, 8 fails; width 4 down to <= 0.02 x 5 = 0.1: 6 halvings (0.0625)
    (5.0, 0.02, 4 + 6),
    # F in [0.125, 0.25): 1, 0.5, 0.25 fail, 0.125 holds; width 0.125 down to <= 0.05 x 0.2: 4 halvings
    (0.2, 0.05, 4 + 4),
])
def test_the_trial_count_follows_the_search_rule(factor, tolerance, by_hand):
    assert trial_count(factor, tolerance) == by_hand


def test_the_plan_gives_the_search_cost_and_error(tmp_path):
    plan = make_plan(load_scene(write(tmp_path, SLOPE)))
    choice = next(c for c in plan.choices if c.topic == "factor of safety")
    assert f"{trial_count(1.5, 0.02)} at F = 1.5" in choice.cost
    assert "F to within 2 %" in choice.error
    assert plan.safety["tolerance"] == pytest.approx(0.02)
    assert plan.slip == {"bedding": True, "tension_crack": True}


def test_the_summary_says_when_the_strength_does_not_decide_f():
    """A search whose failures do not depend on F (SafetyFactor.reason, strength_reduction) gives no
    F in the summary, and its reason and failure in words; a decided one gives F and no such words."""
    from types import SimpleNamespace
    from rockjoint.fem.mechanics.strength_reduction import SafetyFactor
    from rockjoint.scenes.summary import safety_lines
    reason = "every failed trial stopped at load factor 0.42: the failure does not depend on the strength"
    failure = "load stepping failed: joint cross_13 cycles between open and stuck"
    for found, decided in ((SafetyFactor(1.25, 1.2, 1.3, 0.01, reason=reason, failure=failure), False),
                           (SafetyFactor(1.25, 1.2, 1.3, 0.01, failure=failure), True)):
        text = "\n".join(safety_lines(SimpleNamespace(safety=SimpleNamespace(found=found, seconds=1.0, moving=[]),
                                                      rows=[]), 30))
        assert ("1.25" in text) == decided and ("does not depend on the strength" in text) != decided
        assert failure in text


def test_a_benched_slope_moves_its_crest_back(tmp_path):
    """Two benches 3 m wide: the section's crest 6 m further from the toe than without them (the
    faces still rise 30 m at 65°), the ground behind it as long."""
    import math
    from rockjoint.scenes import slope_keys
    text = SLOPE.replace("  face_angle: 65 deg", "  face_angle: 65 deg\n  benches: [{elevation: 10 m, width: 3 m}, "
                                                 "{elevation: 20 m, width: 3 m}]")
    g = load_scene(write(tmp_path, text))["geometry"]
    crest = slope_keys.section(g).crest
    assert crest[0] == pytest.approx(30.0 + 30.0 / math.tan(math.radians(65.0)) + 6.0, rel=1e-12)
    assert crest[1] == pytest.approx(15.0 + 30.0)
