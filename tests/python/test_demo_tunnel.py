"""The tunnel demo runs as it is (coarse: --quick), serially and on 2 ranks.

References: the intact tunnel's wall convergence is Kirsch's excavation displacement
(rockjoint.reference.kirsch, computed here) up to the mesh and the domain: at the quick mesh
(P1, h = a/4 at the wall) bench/results/kirsch.md gives a discretisation error of at most 0.07
p a/(2G) and the W/a = 20 rollers another 0.07, so the bound is 0.2 p a/(2G). The jointed tunnel
must converge more than the intact one at the crown and the sidewalls (the joints add compliance),
and 2 ranks must print the serial figures.
"""
import math
import re

import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem")

import demo_runner  # noqa: E402
from rockjoint.reference import KirschSolution  # noqa: E402

A, SIGMA_V, K0, E, NU = 4.0, 2700.0 * 9.81 * 300.0, 0.5, 50e9, 0.25
NAMES = ("right sidewall", "crown", "left sidewall", "invert")


def run_demo(out, ranks):
    r = demo_runner.run_demo("demo_tunnel.py", out, ranks, ("--quick",))
    for name in ("tunnel.png", "tunnel.txt", "tunnel_intact.xdmf", "tunnel_jointed.xdmf",
                 "tunnel_jointed_joints.xdmf", "tunnel_intact_stress.xdmf", "tunnel_jointed_stress.xdmf"):
        assert (out / name).exists(), name
    text = (out / "tunnel.txt").read_text()
    rows = {}
    for name in NAMES:
        m = re.search(rf"^wall convergence {name} \[mm\]\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)%$", text, re.M)
        assert m, text
        rows[name] = tuple(float(v) for v in m.groups())  # (Kirsch, intact, jointed [mm], share [%])
    for name in NAMES[:2]:
        m = re.search(rf"^hoop stress {name} \[MPa\]\*\s+(\S+)\s+(\S+)\s+(\S+)$", text, re.M)
        assert m, text
        rows["hoop " + name] = tuple(float(v) for v in m.groups())
    for key in ("closure change", "opened", "lining"):
        rows[key] = tuple(float(v) for v in re.findall(r"-?\d+\.\d+", re.search(rf"^.*{key}.*$", text, re.M)[0]))
    assert "demo wall time" in r.stdout
    return rows


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def test_intact_wall_convergence_is_kirsch_and_joints_add_to_it(serial):
    kirsch = KirschSolution(A, SIGMA_V, K0, E, NU)
    unit = SIGMA_V * A / (2 * kirsch.shear_modulus) * 1e3  # p a / (2G) [mm]
    for name, theta in zip(NAMES, (0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi)):
        expected = -kirsch.excavation_displacement(A, theta)[0] * 1e3
        k, intact, jointed, _ = serial[name]
        assert k == pytest.approx(expected, abs=1e-3)  # the demo's Kirsch column (3 decimals)
        assert intact == pytest.approx(expected, abs=0.2 * unit), name
        assert jointed > intact, name


def test_two_ranks_print_the_serial_figures(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    assert parallel.keys() == serial.keys()
    for key in serial:
        assert parallel[key] == pytest.approx(serial[key], abs=1.5e-3), key
