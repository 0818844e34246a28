# SPDX-License-Identifier: MIT
"""The planner's choices, each checked by running or against the evidence it cites:

- a 2D scene is solved in 2D (the mesh the run solves has gdim 2), and cannot be forced to 3D;
- the table covers what the scene reaches: after the run, every joint's largest closure and normal
  stress are inside its table (tunnel: opening concentration; blocky: block corners);
- the ladder's numbers are the bench's: bench/results/accuracy_ladder.json (the planner's source)
  says what bench/results/accuracy_ladder.md says, row by row;
- the rung picked for a topography meets the budget by the bench's JSON, read here on its own,
  and no rung of less total cost does; the exact contact curve (BEM) is a rung;
- the strength the slip decision uses is the joint's own (JointStrength.shear_strength, its
  maximum_friction_angle included), checked against the closed forms;
- slip is left out where joints stay far from their envelope and put in where they reach it; run
  both ways, leaving it out changes the answer by less than the budget.
"""
import json
import math
import os
import re

import numpy as np
import pytest
from scipy import stats

from rockjoint.scenes import SceneError, load_scene, make_plan, planner
from rockjoint.scenes import ladder, stresses
from fe_stack import require_fe
from scene_cases import COLUMN, SCENES, SOURCE, cli, write

LADDER_FILE = os.path.join(SOURCE, "bench", "results", "accuracy_ladder.md")
LADDER_JSON = os.path.join(SOURCE, "bench", "results", "accuracy_ladder.json")
FAMILIES = ("granite-like", "sandstone-like")


def ladder_file_rows():
    """{(family, row label): (mean closure error [-], cost [µs])} parsed from the result file."""
    rows, family = {}, None
    for line in open(LADDER_FILE, encoding="utf-8"):
        if line.startswith("## "):
            family = line[3:].strip()
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if family and len(cells) == 8 and cells[1].endswith("%"):
            rows[family, cells[0]] = (float(cells[1].rstrip(" %")) / 100, float(cells[6]))
    return rows


def test_two_d_scene_is_planned_in_2d_and_cannot_be_forced_to_3d(tmp_path):
    plan = make_plan(load_scene(os.path.join(SCENES, "tunnel.yaml")))
    assert plan.dimension == 2
    bad = write(tmp_path, COLUMN + "plan: {dimension: 3}\n")
    with pytest.raises(SceneError, match="plan.dimension"):
        make_plan(load_scene(bad))
    code, out, _ = cli("plan", os.path.join(SCENES, "tunnel.yaml"))
    assert code == 0 and "2D plane strain" in out and "cost:" in out and "error:" in out


def ladder_rows():
    """{topography-derived law key: its row of the ladder's JSON} (the registry's records)."""
    from rockjoint import law_registry
    return {k: r.ladder_row for k, r in law_registry.topography_laws().items() if r.ladder_row}


def bench_json():
    with open(LADDER_JSON, encoding="utf-8") as fh:
        return json.load(fh)


def test_ladder_json_says_what_the_report_says():
    """Every law row of the .md (mean closure error per joint type, cost per evaluation) equals
    the JSON's to the .md's rounding; the planner reads the JSON, people read the .md."""
    data, rows = bench_json(), ladder_file_rows()
    by_label = {law["label"]: law for law in data["laws"].values()}
    checked = 0
    for (family, label), (error, cost) in rows.items():
        law = by_label[label.replace(" **(recommended)**", "")]
        if family in FAMILIES:
            assert round(100 * law["families"][family]["closure_error_mean"], 1) == pytest.approx(100 * error, abs=1e-9), \
                (family, label)
            assert round(law["evaluation_seconds"] * 1e6, 2) == pytest.approx(cost, abs=1e-9), label
            checked += 1
    assert checked == 2 * len(data["laws"])
    # the exact contact's errors: the .md's section against the JSON
    text = open(LADDER_FILE, encoding="utf-8").read()
    section = text[text.index("## Exact contact as a rung"):]
    for family in FAMILIES:
        row = re.search(r"^\| " + family + r" \| (\d+) \(([\d, ]+)\) \| ([\d., ]+) % \| ([\d.]+) % \| "
                        r"([\d.]+) % \| ([\d.]+) % \| ([\d.]+) % \| ([\d.]+) % \|$", section, re.M)
        e = data["bem"]["families"][family]
        count, seeds, per_joint, *values = row.groups()
        assert int(count) == len(e["resolution_errors"]) and seeds.split(", ") == list(e["resolution_errors"])
        assert [float(x) for x in per_joint.split(", ")] == [round(100 * v, 1) for v in e["resolution_errors"].values()]
        per = list(e["resolution_errors"].values())
        assert [float(x) for x in values] == [round(100 * e["resolution_error_mean"], 1), round(100 * max(per), 1),
                                              round(100 * prediction_limit(per), 1),
                                              round(100 * e["resolution_error_max"], 1),
                                              round(100 * e["table_error"], 2)], family
        assert e["resolution_error_mean"] == pytest.approx(np.mean(per), rel=1e-12)
        assert max(per) <= e["resolution_error_max"]
    # the planner's rungs are the JSON's rows: a law's error the upper prediction limit of its
    # per-joint errors against the scan's BEM plus that of the BEM's resolution errors, the exact
    # contact's that resolution limit plus its table's
    rungs = ladder.by_key()
    exact = data["bem"]["families"]
    for key, row in ladder_rows().items():
        family = data["laws"][row]["families"]
        assert rungs[key].errors == pytest.approx(
            {f: prediction_limit(family[f]["closure_errors"]) + prediction_limit(
                list(exact[f]["resolution_errors"].values())) for f in FAMILIES}, rel=1e-12)
        assert all(family[f]["closure_error_mean"] == pytest.approx(np.mean(family[f]["closure_errors"]), rel=1e-12)
                   for f in FAMILIES)
    assert rungs[ladder.EXACT_CONTACT].errors == pytest.approx({
        f: prediction_limit(list(exact[f]["resolution_errors"].values())) + exact[f]["table_error"]
        for f in FAMILIES}, rel=1e-12)


def prediction_limit(samples, t=None):
    """The 95 % upper prediction limit for one more sample, written here on its own: mean +
    t_0.95,n-1 s sqrt(1 + 1/n), Student's quantile from scipy (checked against a printed table in
    test_upper_prediction_limit)."""
    x = np.asarray(samples, dtype=float)
    n = x.size
    return x.mean() + stats.t.ppf(0.95, n - 1) * x.std(ddof=1) * math.sqrt(1 + 1 / n)


def test_upper_prediction_limit():
    """mean + t s sqrt(1 + 1/n) with Student's t from a printed table (t_0.95 = 2.132 for 4
    degrees of freedom, 1.833 for 9): 1..5 → 3 + 2.132 · 1.5811 · 1.0954; a constant sample → its
    value; bad samples named."""
    assert ladder.upper_prediction_limit([1, 2, 3, 4, 5]) == pytest.approx(3 + 2.132 * math.sqrt(2.5) * math.sqrt(1.2),
                                                                          rel=2e-4)
    ten = np.arange(10.0)
    assert ladder.upper_prediction_limit(ten) == pytest.approx(4.5 + 1.833 * ten.std(ddof=1) * math.sqrt(1.1), rel=2e-4)
    assert ladder.upper_prediction_limit([0.2, 0.2, 0.2]) == pytest.approx(0.2, rel=1e-12)
    for bad in ([0.1], [0.1, float("nan")], []):
        with pytest.raises(ValueError, match="at least 2 finite samples"):
            ladder.upper_prediction_limit(bad)


def rung_seconds(data, row, points, tolerance):
    """Total cost of a rung by the JSON, interpolated here on its own (log-log in the points)."""
    def interp(table):
        xs = sorted(table, key=float)
        lo = max([x for x in xs if float(x) <= points] or xs[:1], key=float)
        hi = min([x for x in xs if float(x) > float(lo)] or xs[-1:], key=float)
        if lo == hi:
            lo, hi = xs[-2], xs[-1]
        p = math.log(table[hi] / table[lo]) / math.log(float(hi) / float(lo))
        return table[lo] * (points / float(lo)) ** p
    if row is None:
        return interp(data["bem_seconds"])
    tab = {float(t): v for t, v in data["laws"][row]["tabulation_seconds"].items() if v is not None}
    tight = min(tab)
    return interp(data["laws"][row]["law_seconds"]) + tab[max(t for t in tab if t <= max(tolerance, tight))]


@pytest.mark.parametrize("budget", [0.02, 0.05, 0.08, 0.10, 0.20, 0.25, 0.30, 0.40])
def test_rung_meets_the_budget_at_least_total_cost(tmp_path, budget):
    text = open(os.path.join(SCENES, "lab_closure_test.yaml"), encoding="utf-8").read()
    text = re.sub(r"error_budget: .*", f"error_budget: {budget * 100:g} %", text)
    scene = load_scene(write(tmp_path, text))
    plan = make_plan(scene)
    points, tol = scene["joints"]["joint"]["law"]["topography"]["points"], plan.table_tolerance
    data = bench_json()
    error, seconds = {}, {}
    exact = data["bem"]["families"]
    for key, row in ladder_rows().items():
        error[key] = max(prediction_limit(data["laws"][row]["families"][f]["closure_errors"])
                         + prediction_limit(list(exact[f]["resolution_errors"].values())) for f in FAMILIES)
        seconds[key] = rung_seconds(data, row, points, tol)
    error[ladder.EXACT_CONTACT] = max(prediction_limit(list(exact[f]["resolution_errors"].values()))
                                      + exact[f]["table_error"] for f in FAMILIES)
    seconds[ladder.EXACT_CONTACT] = rung_seconds(data, None, points, tol)
    key = plan.laws["joint"]
    choice = next(c for c in plan.choices if c.topic == "law of joint")
    assert f"~{seconds[key]:.2g} s" in choice.cost   # the plan says the cost
    if min(error.values()) <= budget:
        assert error[key] <= budget
        assert all(seconds[k] >= seconds[key] for k in error if error[k] <= budget)
    else:   # nothing meets it: the most accurate rung, and the plan says so
        assert key == min(error, key=error.get)
        assert "no rung meets" in choice.why


def test_slip_decision_uses_the_joints_own_strength():
    """Coulomb: c + σ_n tan φ; Barton: σ_n tan(φ_r + JRC log10(JCS/σ_n)) capped at the strength's
    maximum_friction_angle (50° here: at 0.1 MPa Barton's angle is 30 + 15·3 = 75°)."""
    from rockjoint.joint import make_strength   # the set's strength, as Scene.strengths holds it
    coulomb = make_strength({"model": "coulomb", "friction_angle": math.radians(30), "cohesion": 1e5})
    assert stresses.shear_capacity(coulomb, 2e6) == pytest.approx(1e5 + 2e6 * math.tan(math.radians(30)), rel=1e-12)
    barton = make_strength({"model": "barton", "friction_angle": math.radians(30), "cohesion": 0.0, "jrc": 15.0,
                            "jcs": 100e6, "maximum_friction_angle": math.radians(50)})
    assert stresses.shear_capacity(barton, 0.1e6) == pytest.approx(0.1e6 * math.tan(math.radians(50)), rel=1e-12)
    at_10 = math.radians(30 + 15 * math.log10(100 / 10))
    assert stresses.shear_capacity(barton, 10e6) == pytest.approx(10e6 * math.tan(at_10), rel=1e-12)
    # on a plane at 45° of a uniaxial 0.2 MPa stress: τ = σ_n = 0.1 MPa, so τ/τ_max = 1/tan 50°
    n = [math.sqrt(0.5), math.sqrt(0.5)]
    import numpy as np
    stress = np.array([[0.0, 0.0], [0.0, -0.2e6]])
    assert stresses.mobilised_friction(barton, np.array(n), stress) == pytest.approx(1 / math.tan(math.radians(50)))


@pytest.fixture
def run_scene():
    """The scene runner, for the cases that solve: only they need the FE stack (the plan-only
    cases above and below run without DOLFINx; a module-level skip hid them too)."""
    require_fe()
    from rockjoint.scenes import run_scene
    return run_scene


@pytest.mark.parametrize("name", ["tunnel", "blocky_rock_mass"])
def test_table_covers_what_the_scene_reaches(tmp_path, name, run_scene):
    scene = load_scene(os.path.join(SCENES, name + ".yaml")).at_reduced_size()
    plan = make_plan(scene)
    result = run_scene(scene, plan, str(tmp_path / "out"))
    for row in (r for r in result.rows if r.model == "jointed"):
        for joint_set, (closure, stress) in row.per_set.items():
            table = result.tables[joint_set]
            assert stress < table.table_maximum_stress and closure < table.table_maximum_closure


SHEARED = COLUMN.replace("[0 MPa, -10 MPa]", "[3 MPa, -10 MPa]")   # τ/σ_n = 0.3 < tan 30° = 0.58


def test_slip_left_out_far_from_the_envelope_and_the_answer_barely_changes(tmp_path, run_scene):
    # 2 MPa shear over 10 MPa normal load: τ/(σ_n tan 30°) = 0.35 on the joint, below the 0.5 margin
    text = COLUMN.replace("[0 MPa, -10 MPa]", "[2 MPa, -10 MPa]")
    scene = load_scene(write(tmp_path, text))
    plan = make_plan(scene)
    assert plan.slip == {"joint": False}
    forced = load_scene(write(tmp_path, text + "plan: {slip: true}\n", "forced.yaml"))
    plan_forced = make_plan(forced)
    assert plan_forced.slip == {"joint": True}
    a = run_scene(scene, plan, str(tmp_path / "a"))
    b = run_scene(forced, plan_forced, str(tmp_path / "b"))
    for stage in ("load",):
        ua, ub = a.row("jointed", stage).monitors["top"], b.row("jointed", stage).monitors["top"]
        intact = a.row("intact", stage).monitors["top"]
        for k in (0, 1):   # the joints' share of the top's movement, both components
            share = abs(ua[k] - intact[k])
            assert share > 0 and abs(ua[k] - ub[k]) < scene["error_budget"] * share, (k, ua, ub)


def test_slip_put_in_where_the_joint_reaches_its_envelope(tmp_path, run_scene):
    # the shear box: 0.8 MPa shear over 2 MPa normal load, mobilised friction 0.69 of tan 30° on
    # average and more at the box's edges (bending): the plan includes slip and the run slips there
    scene = load_scene(os.path.join(SCENES, "direct_shear.yaml")).at_reduced_size()
    plan = make_plan(scene)
    assert plan.slip == {"joint": True}
    row = run_scene(scene, plan, str(tmp_path / "c")).row("jointed", "shear")
    assert row.slipping > 0


def test_slip_bound_below_the_margin_is_left_out(tmp_path):
    # mobilised friction 0.3/0.577 = 0.52 just above the 0.5 margin: included; 2 MPa shear: left out
    assert make_plan(load_scene(write(tmp_path, SHEARED))).slip == {"joint": True}
    calm = COLUMN.replace("[0 MPa, -10 MPa]", "[2 MPa, -10 MPa]")
    assert make_plan(load_scene(write(tmp_path, calm, "calm.yaml"))).slip == {"joint": False}


def test_refinement_only_near_joints_and_openings(tmp_path):
    tunnel = make_plan(load_scene(os.path.join(SCENES, "tunnel.yaml")))
    assert tunnel.joint_size < tunnel.mesh_size and tunnel.opening_size < tunnel.mesh_size
    plain = COLUMN.replace("geometry: {kind: column, width: 100 mm, height: 100 mm, joint_heights: [50 mm]}",
                           "geometry: {kind: block, size: [100 mm, 100 mm]}")
    start, end = plain.index("joints:\n"), plain.index("supports:")
    plain = plain[:start] + plain[end:]
    plan = make_plan(load_scene(write(tmp_path, plain)))
    assert plan.joint_size is None and plan.opening_size is None and plan.laws == {}
    off = make_plan(load_scene(write(tmp_path, COLUMN + "plan: {refine: false}\n", "off.yaml")))
    assert off.joint_size is None


def test_the_reduced_scene_is_built_once_and_leaves_the_scene_as_it_was():
    # issue 44, item 2: the `reduced:` section applied before planning, read as any scene
    scene = load_scene(os.path.join(SCENES, "tunnel.yaml"))
    full = make_plan(scene)
    small = scene.at_reduced_size()
    r = scene.data["reduced"]
    assert small.reduced and not scene.reduced
    assert small.data["mesh"]["size"] == r["mesh_size"] != scene.data["mesh"]["size"]
    assert small.data["joints"]["bedding"]["law"]["topography"]["points"] == r["topography_points"]
    assert scene.data["joints"]["bedding"]["law"]["topography"]["points"] != r["topography_points"]
    assert all("steps" not in stage for stage in small.data["stages"])
    plan = make_plan(small)
    assert plan.reduced and plan.mesh_size == r["mesh_size"] and plan.load_steps == r["load_steps"]
    assert make_plan(scene).text() == full.text()      # the scene itself is unchanged
    assert plan.laws == {"bedding": full.laws["bedding"]}   # a law the scene gives has no key
