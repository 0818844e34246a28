# SPDX-License-Identifier: MIT
"""The tunnel below a water table (demos/demo_tunnel_below_water_table.py) runs as it is (--quick), serially and
on 2 ranks, and its water obeys what physics guarantees, whatever the coupling:

- before excavation every boundary keeps the table's head and nothing drains: the water in the
  joints is hydrostatic, p = ρ g (z_table - z) at every node of the network;
- a drained opening takes water in (inflow > 0) and the network conserves it (the boundaries'
  flows add up to 0); every head lies between the lowest and the highest head given (the discrete
  maximum principle of the network's P1 conductances): between the opening wall's elevations
  (h = z there, p = 0) and the table's;
- a lined opening lets nothing out: no flow anywhere, the water stays hydrostatic;
- one way, the joints keep the table's water: the largest p is ρ g (z_table - the lowest joint
  point);
- the intact rock holds no water: its convergence is the same in every run, positive (the wall
  moves into the opening), and the joints add compliance (jointed >= intact);
- 2 ranks print the serial figures.

Which of dry, one way and two way converges most is not asserted: physics does not order them.
"""
import json

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402

RHO_G = 998.2 * 9.80665                   # water at 20 °C [Pa/m]
CENTRE, RADIUS = np.array([40.0, 40.0]), 4.0
WET = ("one way", "two way", "one way, lined")


def run_demo(out, ranks):
    r = demo_runner.run_demo("demo_tunnel_below_water_table.py", out, ranks, ("--quick",))
    assert "demo wall time" in r.stdout
    for name in ("tunnel_water.txt", "tunnel_water.json", "two_way/scene.png", "two_way/jointed_flow.xdmf"):
        assert (out / name).exists(), name
    with open(out / "tunnel_water.json", encoding="utf-8") as f:
        return json.load(f)


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def network(serial, run, stage):
    n = serial["answers"][run]["networks"][stage]
    return np.asarray(n["nodes"]), np.asarray(n["head"]), np.asarray(n["pressure"]), n["flow_rates"]


@pytest.mark.parametrize("run", WET)
def test_before_excavation_the_water_is_hydrostatic(serial, run):
    nodes, head, p, rates = network(serial, run, "in-situ")
    table = serial["table_m"]
    np.testing.assert_allclose(p, RHO_G * (table - nodes[:, 1]), rtol=0, atol=1e-9 * RHO_G * table)
    assert max(abs(q) for q in rates.values()) < 1e-9


@pytest.mark.parametrize("run", ["one way", "two way"])
def test_a_drained_opening_takes_water_in_and_the_network_conserves_it(serial, run):
    nodes, head, p, rates = network(serial, run, "excavation")
    inflow = serial["answers"][run]["jointed"]["inflow"]
    assert inflow > 0 and inflow == pytest.approx(-rates["opening"], rel=1e-12)
    assert abs(sum(rates.values())) < 1e-9 * inflow
    wall = np.abs(np.linalg.norm(nodes - CENTRE, axis=1) - RADIUS) < 1e-6
    assert wall.sum() > 4 and np.all(np.abs(p[wall]) < 1e-9 * RHO_G * serial["table_m"])
    reached = ~np.isnan(head)
    tolerance = 1e-9 * serial["table_m"]
    assert head[reached].min() >= CENTRE[1] - RADIUS - tolerance
    assert head[reached].max() <= serial["table_m"] + tolerance


def test_a_lined_opening_lets_nothing_out(serial):
    nodes, head, p, rates = network(serial, "one way, lined", "excavation")
    drained = serial["answers"]["one way"]["jointed"]["inflow"]
    assert "opening" not in rates and max(abs(q) for q in rates.values()) < 1e-9 * drained
    np.testing.assert_allclose(p, RHO_G * (serial["table_m"] - nodes[:, 1]), rtol=0,
                               atol=1e-9 * RHO_G * serial["table_m"])
    assert serial["answers"]["one way, lined"]["jointed"]["inflow"] == 0.0


def test_one_way_the_joints_keep_the_tables_water(serial):
    nodes, *_ = network(serial, "one way", "excavation")
    lowest = nodes[:, 1].min()
    assert serial["answers"]["one way"]["jointed"]["max_pressure_MPa"] == pytest.approx(
        RHO_G * (serial["table_m"] - lowest) * 1e-6, rel=1e-12)
    assert serial["answers"]["dry"]["jointed"]["max_pressure_MPa"] == 0.0


def test_the_intact_rock_holds_no_water_and_the_joints_add_compliance(serial):
    intact = [a["intact"]["convergence_mm"] for a in serial["answers"].values()]
    assert intact[0] > 0 and max(intact) - min(intact) <= 1e-9 * intact[0]
    for run, answer in serial["answers"].items():
        assert answer["jointed"]["convergence_mm"] >= answer["intact"]["convergence_mm"], run


def test_two_ranks_print_the_serial_figures(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    for run, answer in serial["answers"].items():
        for model in ("jointed", "intact"):
            for key, value in answer[model].items():
                if key == "flow_rates":
                    for b, q in value.items():
                        assert parallel["answers"][run][model][key][b] == pytest.approx(q, rel=1e-6, abs=1e-9), (run, b)
                else:
                    assert parallel["answers"][run][model][key] == pytest.approx(value, rel=1e-6, abs=1e-9), (run, key)
