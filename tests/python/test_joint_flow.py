# SPDX-License-Identifier: MIT
"""Steady flow along the joint network (rockjoint.fem.water.joint_flow, docs/flow.md) against
the closed form of n parallel joints between two heads (joint_flow_cases.py), 2D and 3D; the head
falls linearly along each joint; a closed joint carries nothing; bad input is refused by name."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from joint_flow_cases import HEADS, WIDTH, cubic_law, expected_rate, solved_column  # noqa: E402
from rockjoint.fem.water.joint_flow import Fluid, network_flow  # noqa: E402


@pytest.mark.parametrize("dim, heights", [(2, (1.0, 2.0)), (2, (0.7, 1.5, 2.4)), (3, (1.0, 2.0))])
def test_parallel_joints_carry_the_closed_form_rate(dim, heights):
    model = solved_column(dim, heights)
    flow = network_flow(model, {f"joint_{i + 1}": cubic_law for i in range(len(heights))}, HEADS)
    q = expected_rate(dim, len(heights))
    assert flow.flow_rates["left"] == pytest.approx(q, rel=1e-9)
    assert flow.flow_rates["right"] == pytest.approx(-q, rel=1e-9)
    # the head falls linearly from left to right along every joint (uniform T)
    linear = HEADS["left"] + (HEADS["right"] - HEADS["left"]) * flow.nodes[:, 0] / WIDTH
    np.testing.assert_allclose(flow.head, linear, rtol=0, atol=1e-9 * HEADS["left"])
    assert flow.unreached_nodes == 0


def test_a_closed_joint_carries_nothing_and_its_nodes_are_unreached():
    model = solved_column(2, (1.0, 2.0))
    laws = {"joint_1": cubic_law, "joint_2": lambda d: np.zeros_like(d)}
    flow = network_flow(model, laws, HEADS)
    assert flow.flow_rates["left"] == pytest.approx(expected_rate(2, 1), rel=1e-9)
    tags = flow.element_tags
    closed = np.unique(flow.elements[tags == model.dmesh.joint_tag("joint_2")])
    inside = closed[(flow.nodes[closed, 0] > 0) & (flow.nodes[closed, 0] < WIDTH)]
    assert inside.size == closed.size - 2          # its two ends keep the heads given there
    assert np.all(np.isnan(flow.head[inside])) and flow.unreached_nodes == inside.size


def test_bad_input_is_refused_by_name():
    model = solved_column(2, (1.0, 2.0))
    laws = {"joint_1": cubic_law, "joint_2": cubic_law}
    with pytest.raises(ValueError, match="joint_2"):
        network_flow(model, {"joint_1": cubic_law}, HEADS)
    with pytest.raises(ValueError, match="joint_9"):
        network_flow(model, dict(laws, joint_9=cubic_law), HEADS)
    with pytest.raises(ValueError, match="head on 'left'"):
        network_flow(model, laws, {"left": float("nan")})
    with pytest.raises(ValueError, match="unknown boundary 'east'"):
        network_flow(model, laws, {"east": 1.0})
    with pytest.raises(ValueError, match="joint 'joint_1'.*>= 0"):
        network_flow(model, dict(laws, joint_1=lambda d: -np.ones_like(d)), HEADS)
    with pytest.raises(ValueError, match="viscosity"):
        Fluid(viscosity=-1.0)


def test_flow_passes_from_one_joint_into_another_where_they_meet():
    """A T-junction in a 2 m x 2 m section: joint A across it at y = 1 m, joint B up from A to the
    top at x = 1 m; heads on the left side and the top. The flow enters A, turns into B at the
    junction and leaves through the top; A's right half is a dead end (no head there). Closed form:
    1 m of A and 1 m of B in series, Q = c Δh / (1/T_A + 1/T_B), c = ρ g / μ."""
    from mpi4py import MPI
    import rockjoint
    from rockjoint import meshes
    from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
    from rockjoint.meshes.joint_geometry import Joint

    comm = MPI.COMM_WORLD
    jm = meshes.jointed_block((2.0, 2.0), [Joint((1.0, 1.0), 0.0, 90.0, "A"),
                                           Joint((1.0, 1.5), 90.0, 90.0, "B", bounded_by=("A",))],
                              mesh_size=0.25, comm=comm)
    law = rockjoint.BartonBandis(1e10, 1e-3)
    model = JointedRockModel(distribute(jm, comm), rock=(20e9, 0.25), joints={"A": law, "B": law},
                             newton=NewtonOptions(verbose=False), shear_stiffness=1e9)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -1e6))
    model.add_traction("right", (-1e6, 0.0))
    model.solve()
    t_a, t_b = 1e-10, 4e-10                 # [m³]
    flow = network_flow(model, {"A": lambda d: np.full_like(d, t_a), "B": lambda d: np.full_like(d, t_b)},
                        {"left": 10.0, "top": 4.0})
    q = Fluid().conductivity_factor * (10.0 - 4.0) / (1.0 / t_a + 1.0 / t_b)
    assert flow.flow_rates["left"] == pytest.approx(q, rel=1e-9)
    assert flow.flow_rates["top"] == pytest.approx(-q, rel=1e-9)
    junction = np.argmin(np.linalg.norm(flow.nodes - [1.0, 1.0], axis=1))
    assert flow.head[junction] == pytest.approx(10.0 - q / (Fluid().conductivity_factor * t_a), rel=1e-9)
    dead_end = flow.nodes[:, 0] > 1.0 + 1e-9
    np.testing.assert_allclose(flow.head[dead_end], flow.head[junction], rtol=1e-9)


@pytest.mark.parametrize("dim", [2, 3])
def test_smeared_set_carries_what_its_discrete_joints_carry(dim):
    """Three joints every s = 1 m in the 3 m column (the network, each joint's T from its closure)
    against the same set smeared into the intact column, k = T/s (I - n⊗n) (darcy.py, F2-F3):
    the same flow rate, and both the closed form n (ρ g / μ) T Δh W / L."""
    from mpi4py import MPI
    from rockjoint import meshes
    from rockjoint.fem import distribute
    from rockjoint.fem.water.darcy import darcy_flow, equivalent_permeability
    from joint_flow_cases import HEIGHT, LOAD, KNI, VM

    heights = (0.5, 1.5, 2.5)
    discrete = network_flow(solved_column(dim, heights), {f"joint_{i + 1}": cubic_law for i in range(3)}, HEADS)
    closure = LOAD * VM / (KNI * VM + LOAD)
    normal = np.eye(dim)[dim - 1]
    k = equivalent_permeability([(normal, HEIGHT / len(heights), float(cubic_law(closure)))], dim)
    intact = distribute(meshes.column(WIDTH, HEIGHT, (), dim=dim, mesh_size=0.5, comm=MPI.COMM_WORLD),
                        MPI.COMM_WORLD)
    smeared = darcy_flow(intact, k, HEADS)
    q = expected_rate(dim, 3)
    assert discrete.flow_rates["left"] == pytest.approx(q, rel=1e-9)
    assert smeared.flow_rates["left"] == pytest.approx(q, rel=1e-9)
    assert smeared.flow_rates["right"] == pytest.approx(-q, rel=1e-9)
    with pytest.raises(ValueError, match="spacing"):
        equivalent_permeability([(normal, 0.0, 1e-12)], dim)


def test_the_network_is_written_for_paraview(tmp_path):
    import meshio
    model = solved_column(2, (1.0, 2.0))
    flow = network_flow(model, {"joint_1": cubic_law, "joint_2": cubic_law}, HEADS)
    path = flow.write(str(tmp_path / "network.xdmf"))
    back = meshio.read(path)
    np.testing.assert_allclose(back.points[:, :2], flow.nodes)
    np.testing.assert_allclose(back.point_data["head_m"], flow.head)
    np.testing.assert_allclose(back.cell_data["transmissivity_m3"][0], flow.element_transmissivity)


@pytest.mark.parametrize("dim", [2, 3])
def test_pressures_and_injected_rates_are_the_closed_form_too(dim):
    """pressures={b: p}: h = z + p/(ρ g) at each node (the same flow as those heads where z is
    constant along the boundary's joints: here z varies, every joint its own head); rates={b: Q}:
    the closed-form rate injected on the left gives back the left head, the boundary's joints
    sharing it (a port), and Q flows out on the right."""
    model = solved_column(dim)
    laws = {"joint_1": cubic_law, "joint_2": cubic_law}
    fluid = Fluid()
    rg = fluid.density * fluid.gravity
    q = expected_rate(dim, 2)
    # pressure p on the right: each joint at height z gets h = z + p/(ρg); the left head fixed
    flow = network_flow(model, laws, {"left": HEADS["left"]}, pressures={"right": rg * (HEADS["right"] - 1.0)})
    # joint_1 (z = 1) sees the right head HEADS["right"], joint_2 (z = 2) one metre more
    one = expected_rate(dim, 1)
    assert flow.flow_rates["left"] == pytest.approx(one + one * (HEADS["left"] - HEADS["right"] - 1.0)
                                                    / (HEADS["left"] - HEADS["right"]), rel=1e-9)
    np.testing.assert_allclose(flow.pressure[np.isclose(flow.nodes[:, 0], WIDTH)], rg * (HEADS["right"] - 1.0),
                               rtol=1e-12)
    injected = network_flow(model, laws, {"right": HEADS["right"]}, rates={"left": q})
    assert injected.port_heads["left"] == pytest.approx(HEADS["left"], rel=1e-9)
    assert injected.flow_rates["left"] == pytest.approx(q, rel=1e-9)
    assert injected.flow_rates["right"] == pytest.approx(-q, rel=1e-9)


def test_bad_boundary_conditions_are_refused_by_name():
    model = solved_column(2)
    laws = {"joint_1": cubic_law, "joint_2": cubic_law}
    with pytest.raises(ValueError, match="heads=.*or pressures="):
        network_flow(model, laws, rates={"left": 1e-6})
    with pytest.raises(ValueError, match="boundary 'left' has two conditions"):
        network_flow(model, laws, HEADS, pressures={"left": 1e5})
    with pytest.raises(ValueError, match="rate on 'left'"):
        network_flow(model, laws, {"right": 1.0}, rates={"left": float("inf")})
    closed = dict(laws, joint_1=lambda d: np.zeros_like(d), joint_2=lambda d: np.zeros_like(d))
    with pytest.raises(ValueError, match="injected on 'left' reaches no boundary"):
        network_flow(model, closed, {"right": 1.0}, rates={"left": 1e-6})
    with pytest.raises(ValueError, match="no joint meets boundary 'top'"):
        network_flow(model, laws, {"right": 1.0}, rates={"top": 1e-6})
