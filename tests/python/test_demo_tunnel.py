# SPDX-License-Identifier: MIT
"""The tunnel demo runs as it is (coarse: --quick), serially and on 2 ranks.

References: the intact tunnel's wall convergence is Kirsch's excavation displacement
(rockjoint.reference.kirsch, computed here) up to the mesh and the domain: at the quick mesh
(P1, h = a/4 at the wall) bench/results/kirsch.md gives a discretisation error of at most 0.07
p a/(2G) and the W/a = 20 rollers another 0.07, so the bound is 0.2 p a/(2G). The jointed tunnel
must converge more than the intact one at the crown and the sidewalls (the joints add compliance);
slipping joints (Coulomb) only add compliance to the elastic ones, so the spans of the opening never
close less (single wall points can: the opening moves as a whole when a wedge slides); the
slipping model's joint points (tunnel_slip_joints.npz) lie on the Coulomb line where they slip and
inside it where they stick (Coulomb's law, eq. (2a) of docs/joint-strength.md, with the φ and c the
demo's comment cites); and 2 ranks must print the serial figures.
"""
import math
import re

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402
from rockjoint.reference import KirschSolution  # noqa: E402

A, SIGMA_V, K0, E, NU = 4.0, 2700.0 * 9.81 * 300.0, 0.5, 50e9, 0.25
NAMES = ("right sidewall", "crown", "left sidewall", "invert")
# Coulomb strength of granite joints: basic friction φ_b = 30° (Barton & Choubey 1977), c = 0
FRICTION_ANGLE, COHESION = math.radians(30.0), 0.0
RESIDUAL_STIFFNESS = 1e6  # [Pa/m], demos/scenes/tunnel.yaml
STICK, SLIP, OPEN = 0, 1, 2  # rockjoint.fem.ShearState values


def run_demo(out, ranks):
    r = demo_runner.run_demo("demo_tunnel.py", out, ranks, ("--quick",))
    for name in ("tunnel.png", "tunnel_joint_slip.png", "tunnel.txt", "tunnel_intact.xdmf", "tunnel_jointed.xdmf",
                 "tunnel_jointed_joints.xdmf", "tunnel_slip.xdmf", "tunnel_slip_joints.xdmf",
                 "tunnel_intact_stress.xdmf", "tunnel_jointed_stress.xdmf", "tunnel_slip_stress.xdmf",
                 "tunnel_flow.xdmf"):
        assert (out / name).exists(), name
    text = (out / "tunnel.txt").read_text()
    rows = {}
    for name in NAMES:
        m = re.search(rf"^wall convergence {name} \[mm\]\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)%$", text, re.M)
        assert m, text
        rows[name] = tuple(float(v) for v in m.groups())  # (Kirsch, intact, jointed, slipping [mm], share [%])
    for name in NAMES[:2]:
        m = re.search(rf"^hoop stress {name} \[MPa\]\*\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)$", text, re.M)
        assert m, text
        rows["hoop " + name] = tuple(float(v) for v in m.groups())
    for key in ("closure change", "opened", "lining"):
        rows[key] = tuple(float(v) for v in re.findall(r"-?\d+\.\d+", re.search(rf"^.*{key}.*$", text, re.M)[0]))
    for name in ("bedding", "cross"):  # points, slipping, fraction [%], farthest [a], max slip [mm]
        m = re.search(rf"^slip {name}\s+(\d+)\s+(\d+)\s+(\S+)%\s+(\S+)\s+(\S+)$", text, re.M)
        assert m, text
        rows["slip " + name] = tuple(float(v) for v in m.groups())
    assert re.search(r"^Newton iterations.*slipping joints \d+, \d+, \d+$", text, re.M), text
    line = re.search(r"^wall convergence hysteretic \[mm\]: (.*)$", text, re.M)[1]
    rows["hysteretic"] = tuple(float(re.search(rf"{name} (\S+)", line)[1]) for name in NAMES)
    m = re.search(r"^hysteretic opened joint points .*: (\d+) of (\d+);.*\(elastic joints: (\d+),", text, re.M)
    assert m, text
    rows["opened hysteretic"] = tuple(float(v) for v in m.groups())
    m = re.search(r"^joint transmissivity after / before.*crown and invert median x(\S+) .*sidewalls median "
                  r"x(\S+) .*all joints x(\S+) to x(\S+)$", text, re.M)
    assert m, text
    rows["transmissivity"] = tuple(float(v) for v in m.groups())
    m = re.search(r"^inflow into the tunnel .*intact rock \(k = (\S+) m²\) (\S+); joints at their in-situ "
                  r"closure (\S+), after excavation (\S+) ", text, re.M)
    assert m, text
    rows["inflow"] = tuple(float(v) for v in m.groups())
    assert "demo wall time" in r.stdout
    return rows


@pytest.fixture(scope="module")
def serial_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("serial")


@pytest.fixture(scope="module")
def serial(serial_dir):
    return run_demo(serial_dir, 1)


def test_intact_wall_convergence_is_kirsch_and_joints_add_to_it(serial):
    kirsch = KirschSolution(A, SIGMA_V, K0, E, NU)
    unit = SIGMA_V * A / (2 * kirsch.shear_modulus) * 1e3  # p a / (2G) [mm]
    for name, theta in zip(NAMES, (0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi)):
        expected = -kirsch.excavation_displacement(A, theta)[0] * 1e3
        k, intact, jointed, _, _ = serial[name]
        assert k == pytest.approx(expected, abs=1e-3)  # the demo's Kirsch column (3 decimals)
        assert intact == pytest.approx(expected, abs=0.2 * unit), name
        assert jointed > intact, name


def test_slip_never_reduces_the_span_closure_of_elastic_joints(serial):
    # Spans (sidewall to sidewall, crown to invert), not single wall points: a wedge sliding into
    # one side moves the opening as a whole, and the far wall's radial displacement can drop
    # (it does at the right sidewall); the closure of a span does not see that translation.
    for pair in ((0, 2), (1, 3)):
        jointed = sum(serial[NAMES[k]][2] for k in pair)
        slipping = sum(serial[NAMES[k]][3] for k in pair)
        assert slipping >= jointed - 2e-3, pair  # the table's 3 decimals, twice
    assert serial["slip bedding"][1] + serial["slip cross"][1] > 0  # some joint slips at excavation


def test_slipping_points_lie_on_the_coulomb_line_and_sticking_points_inside(serial, serial_dir):
    state = np.load(serial_dir / "tunnel_slip_joints.npz")
    sn, shear_state = state["normal_stress"], state["shear_state"]
    tau = np.abs(state["shear_traction"]).reshape(-1)
    strength = COHESION + sn * math.tan(FRICTION_ANGLE)  # [Pa], compression +
    slips, sticks = shear_state == SLIP, shear_state == STICK
    assert slips.any() and sticks.any()
    # A slipping point is on the Coulomb line, or on the residual floor (docs/joint-strength.md,
    # return mapping step 3): where σ_n is so close to zero that the strength has fallen below the
    # residual spring's traction k_r e, it carries k_r e >= the strength, with e, the elastic shear
    # jump, well under 1 mm: under 1 kPa (one point of 36 on the mesh of 2026-11-27, σ_n = 30 Pa).
    on_line = np.isclose(tau, strength, rtol=1e-9, atol=0.0)
    on_floor = (tau >= strength * (1 - 1e-9)) & (tau <= RESIDUAL_STIFFNESS * 1e-3)
    assert np.all((on_line | on_floor)[slips]), (tau[slips], strength[slips])
    assert np.count_nonzero(on_line[slips]) >= 0.9 * np.count_nonzero(slips)
    assert np.all(tau[sticks] <= strength[sticks] * (1 + 1e-9))
    assert np.all(sn[shear_state == OPEN] <= 0.0)  # an open joint carries no compression


def test_stiff_unloading_reduces_crown_and_invert_convergence_and_the_opened_zone(serial):
    """Excavation unloads the bedding joints above the crown and below the invert (σ_v released):
    hysteretic joints (docs/hysteresis.md) unload on branches 3 times stiffer than the virgin curve
    at their in-situ closure, so they open less than elastic joints there: the crown and invert
    converge less (still more than intact rock), and fewer joint points lose over 10 % of their
    in-situ closure."""
    for k, name in enumerate(NAMES):
        if name in ("crown", "invert"):
            intact, elastic = serial[name][1], serial[name][2]
            assert intact < serial["hysteretic"][k] < elastic, name
    opened, total, opened_elastic = serial["opened hysteretic"]
    assert opened < opened_elastic


def test_excavation_opens_bedding_at_the_crown_and_closes_it_at_the_sidewalls(serial):
    """Kirsch: at the crown and invert excavation releases σ_rr, which is the bedding joints'
    normal stress there: they open and pass more water; at the sidewalls the hoop stress, normal
    to the bedding there, rises to ~2.5 σ_v: they close and pass less."""
    crown, side, low, high = serial["transmissivity"]
    assert crown > 1.0 > side and low < 1.0 < high


def test_intact_inflow_lies_between_the_radial_flow_bounds(serial):
    """Darcy through the intact square section (side W = 80 m) into the drained tunnel (a = 4 m),
    far-field head 300 m: the radial-flow closed form Q = 2π K Δh / ln(R/a), K = k ρ g / μ, bounds
    it between the inscribed (R = W/2) and circumscribed (R = W/√2) circles (a larger domain
    passes less); in L/min per metre."""
    k, q = serial["inflow"][:2]
    conductivity = k * 998.2 * 9.80665 / 1.002e-3
    bound = [2 * math.pi * conductivity * 300.0 / math.log(r / 4.0) * 6e4 for r in (40.0 * math.sqrt(2), 40.0)]
    assert bound[0] < q < bound[1]
    assert serial["inflow"][2] > 1e3 * q     # the joints carry the flow


def test_two_ranks_print_the_serial_figures(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    assert parallel.keys() == serial.keys()
    for key in serial:
        assert parallel[key] == pytest.approx(serial[key], abs=1.5e-3), key
