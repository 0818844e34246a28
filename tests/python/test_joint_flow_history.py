# SPDX-License-Identifier: MIT
"""Flow with history in the FE network (docs/flow.md "Transmissivity with history (issue 41)"):
the loaded column of joint_flow_cases.py with two joints, one hysteretic (NormalHysteresis over
Barton-Bandis), one plain Barton-Bandis, loaded to 4 MPa then unloaded to 1 MPa. On unloading
the network carries Σ (ρ g/μ) T_i Δh W/L with T_i the closed form of the law with history at
the joint's closure Δ_i and its largest closure Δ_m,i, both written out here: the branch inverse
Δ = r Δ_m + (1 - r) Δ_m (σ/σ_m)^(1/m) of the hysteretic joint, Barton-Bandis' inverse of the
other (its Δ_m: the running maximum over the stages); a law without history is unchanged."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint import flow  # noqa: E402
from rockjoint.fem import network_flow  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import names_of  # noqa: E402
from rockjoint.fem.water.joint_flow import Fluid  # noqa: E402
from joint_flow_cases import APERTURE, HEADS, LOAD, WIDTH  # noqa: E402
from flow_history_cases import (LOSS, bb_closure, branch_transmissivity, check_coupled_twice,  # noqa: E402
                                coupled_twice, cycled_column, unloaded_closures)


def test_unloaded_network_against_the_closed_form_of_the_law_with_history():
    model = cycled_column()
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=APERTURE, hydraulic_loss=LOSS)
    laws = {"joint_1": law.transmissivity, "joint_2": law}        # a bound method or the law itself
    peak = bb_closure(LOAD)
    closure = unloaded_closures()
    factor = Fluid().conductivity_factor * (HEADS["left"] - HEADS["right"]) / WIDTH
    unloaded = network_flow(model, laws, HEADS)
    tags = names_of(model.dmesh, "joints")
    point_tags = model.solution.gather_joints()["tag"]
    expected = {}
    for name, d in closure.items():
        expected[name] = branch_transmissivity(d, peak)
        np.testing.assert_allclose(unloaded.point_transmissivity[point_tags == tags[name]], expected[name],
                                   rtol=1e-7, err_msg=name)
    assert unloaded.flow_rates["left"] == pytest.approx(factor * sum(expected.values()), rel=1e-7)
    assert unloaded.flow_rates["right"] == pytest.approx(-unloaded.flow_rates["left"], rel=1e-10)
    # the history costs flow: below the virgin law at the same closures (ratio T3 per joint)
    virgin = flow.transmissivity_law("cubic_law", initial_aperture=APERTURE)
    for name, d in closure.items():
        ratio = expected[name] / virgin.transmissivity(d)
        assert ratio == pytest.approx(((1 - LOSS) + LOSS * (APERTURE - peak) / (APERTURE - d)) ** 3, rel=1e-12)
        assert ratio < 0.97
    # at the peak (first stage) the law with history is the virgin law; a law without history is
    # unchanged on unloading (T of the current closure only)
    at_peak = network_flow(model, laws, HEADS, stage=model.stages[0])
    assert at_peak.flow_rates["left"] == pytest.approx(2 * factor * virgin.transmissivity(peak), rel=1e-7)
    plain = network_flow(model, {n: virgin.transmissivity for n in closure}, HEADS)
    assert plain.flow_rates["left"] == pytest.approx(
        factor * sum(virgin.transmissivity(d) for d in closure.values()), rel=1e-7)


@pytest.mark.parametrize("solve", ["steady", "transient"])
def test_coupled_water_keeps_the_largest_closure_of_the_stages_before_it(solve):
    """The coupled solves re-gather the joint state at every iterate: each point's Δ_m is still
    the largest closure of the stages before the coupling (the loading to 4 MPa), not the iterate's
    own closure, so T stays the closed form of the law with history at the final closures."""
    from rockjoint.fem.water.coupled import coupled_steady
    from rockjoint.fem.water.transient import coupled_transient
    model = cycled_column()
    law = flow.transmissivity_law("hydraulic_history", initial_aperture=APERTURE, hydraulic_loss=LOSS)
    laws = {"joint_1": law, "joint_2": law}
    if solve == "steady":
        network = coupled_steady(model, laws, HEADS).network
    else:
        network = coupled_transient(model, laws, 1.0, 2, HEADS).networks[-1]
    state = model.solution.gather_joints()
    closure = np.asarray(state["closure"])
    np.testing.assert_allclose(network.point_transmissivity, branch_transmissivity(closure, bb_closure(LOAD)),
                               rtol=1e-9)
    assert np.all(closure < bb_closure(LOAD))            # unloaded: below the peak, on the branch


def test_coupling_iterates_do_not_enter_the_largest_closure():
    """Two successive two-way coupled solves: Δ_m of every point (C++ point state, gathered) and
    T of the second solve's network are those of the accepted states' closures."""
    model, network, accepted = coupled_twice()
    overshoot = check_coupled_twice(model, network, accepted)
    print(f"overshoot of the first iterate over the accepted closures: {overshoot * 1e6:.3f} µm")
    # Δ_m is set only whole and finite, named
    n = model.interface.num_points
    with pytest.raises(ValueError, match="set_maximum_closure"):
        model.interface.set_maximum_closure(np.zeros(n + 1))
    with pytest.raises(ValueError, match="entry 0 is nan"):
        model.interface.set_maximum_closure(np.full(n, np.nan))
