# SPDX-License-Identifier: MIT
"""Past a law's range is never silent (issue 39, item 1), serially, in every path: the user's
SNES problem (JointedNonlinearProblem), JointCoupling driven by the user's own solver (the check
at commit_state), and JointedRockModel (once per stage).

The case (law_range_case): a uniaxial column whose joint carries σ_n = 10 MPa exactly (closed
form), with a Barton-Bandis law tabulated to 2 MPa: every joint point is past the table and
closes on the table's linear continuation, Δ_max + (σ - σ_max)/k(Δ_max), not on the law's
Δ(σ). A table to 30 MPa covers the load and must stay silent. The status codes and the
gathered summary are checked against the point state itself.
"""
import logging
import os
import warnings

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint.continuum import EquivalentContinuum, JointSet  # noqa: E402
from rockjoint.fem import (BeyondRangeError, JointCoupling, JointedRockModel, NewtonOptions,  # noqa: E402
                                    RangeWarning, ShearState, Status)

from rockjoint.fem import joint_behaviours  # noqa: E402
from rockjoint.fem.mechanics.law_range import law_range  # noqa: E402

import law_range_case as case  # noqa: E402

COMM = MPI.COMM_SELF


@pytest.fixture(scope="module")
def dmesh():
    return case.column(COMM)


def range_warnings(record) -> list:
    return [str(w.message) for w in record if issubclass(w.category, RangeWarning)]


def test_a_table_past_its_range_warns_after_the_snes_solve(dmesh):
    problem = case.problem(dmesh, case.SHORT)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        problem.solve()
    assert problem.solver.getConvergedReason() > 0
    (message,) = range_warnings(record)
    assert "joint 'joint_1'" in message and "σ_n reaches 10 MPa" in message, message
    assert "its table covers σ_n 0 - 2 MPa" in message and "linear continuation" in message, message
    # What the warning is about: the closure is the table's continuation, 0.722 mm, where the law
    # gives 0.500 mm (docs/user-model.md quotes both).
    state = problem.coupling.state(problem.u)
    np.testing.assert_allclose(state["normal_stress"], case.LOAD, rtol=1e-9)
    np.testing.assert_allclose(state["closure"], case.continued_closure(2e6, case.LOAD), rtol=1e-5)
    assert (round(case.continued_closure(2e6, case.LOAD) * 1e3, 3), round(case.law_closure(case.LOAD) * 1e3, 3)) \
        == (0.722, 0.5)
    assert np.all(state["status"] == int(Status.validity_limit))


def test_strict_mode_raises_a_named_error(dmesh):
    problem = case.problem(dmesh, case.SHORT, beyond_range="raise")
    with pytest.raises(BeyondRangeError, match=r"joint 'joint_1': \d+ of \d+ points past .* reaches 10 MPa"):
        problem.solve()
    with pytest.raises(ValueError, match=r"beyond_range must be one of \['warn', 'raise'\], got 'loud'"):
        case.problem(dmesh, case.SHORT, beyond_range="loud")


def test_a_table_that_covers_the_load_is_silent(dmesh):
    problem = case.problem(dmesh, case.LONG)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RangeWarning)
        problem.solve()
        problem.coupling.commit_state()
    summary = problem.coupling.summary(problem.u)["joint_1"]
    assert summary.beyond_range == 0 and summary.status["contact"] == summary.points > 0
    np.testing.assert_allclose(problem.coupling.state(problem.u)["closure"], case.law_closure(case.LOAD),
                               rtol=1e-4)  # the table's own tolerance, below its last knot


def test_the_users_own_solver_is_warned_at_commit_state_once(dmesh):
    """Driving the SNES directly (no problem.solve()): the check comes with commit_state, on the
    state of the last residual, and only once for that state."""
    problem = case.problem(dmesh, case.SHORT)
    problem.u.x.petsc_vec.copy(problem.x)
    problem.solver.solve(None, problem.x)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        problem.coupling.commit_state()
        problem.coupling.commit_state()
    (message,) = range_warnings(record)
    assert "joint 'joint_1'" in message and "σ_n reaches 10 MPa" in message


def test_the_summary_is_the_point_state_gathered(dmesh):
    problem = case.problem(dmesh, case.SHORT)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RangeWarning)
        problem.solve()
    state = problem.coupling.state(problem.u)
    s = problem.coupling.summary(problem.u)["joint_1"]
    assert s.points == state["closure"].size > 0
    assert (s.min_closure, s.max_closure) == (state["closure"].min(), state["closure"].max())
    assert (s.min_normal_stress, s.max_normal_stress) == (state["normal_stress"].min(), state["normal_stress"].max())
    assert s.max_shear_traction == np.abs(state["shear_traction"]).max()
    assert s.status == {st.name: int(np.count_nonzero(state["status"] == int(st)))
                        for st in Status.__members__.values()}
    assert s.shear_state == {st.name: int(np.count_nonzero(state["shear_state"] == int(st)))
                             for st in ShearState.__members__.values()}
    assert s.beyond_range == s.points == s.shear_state["stick"]


def test_jointed_rock_model_warns_once_per_stage_and_raises_in_strict_mode(dmesh, caplog):
    def model(**kw):
        m = JointedRockModel(dmesh, rock=(case.E, case.NU), joints={"joint_1": case.SHORT}, shear_stiffness=1e9,
                             plane="strain", newton=NewtonOptions(verbose=False), **kw)
        m.fix("bottom", "y")
        m.fix("left", "x")
        m.add_traction("top", (0.0, -case.LOAD))
        return m

    with warnings.catch_warnings(record=True) as record, caplog.at_level(logging.WARNING):
        warnings.simplefilter("always")
        model().solve(load_steps=4, name="load")
    (message,) = range_warnings(record)   # one per stage, not one per load step
    assert "in stage 'load'" in message and "joint 'joint_1'" in message and "σ_n reaches 10 MPa" in message
    # said once: as the warning, not again as a log record (the CLI prints warnings as lines)
    assert [r.name for r in caplog.records if "past its range" in r.getMessage()] == []
    with pytest.raises(BeyondRangeError, match="in stage 'load'"):
        model(beyond_range="raise").solve(name="load")


def test_status_codes_are_the_documented_enum():
    """Every per-point status is a named rockjoint.Status value with its meaning in the binding
    and a row in docs/user-model.md."""
    doc = open(os.path.join(os.path.dirname(__file__), "..", "..", "docs", "user-model.md"), encoding="utf-8").read()
    assert Status is rockjoint.Status
    for status in Status.__members__.values():
        assert f"| {int(status)} | `{status.name}` |" in doc, status.name
    assert "validity_limit : 2: past the law's range" in Status.__doc__


def test_boundary_tag_names_the_same_tags_as_the_mesh(dmesh):
    for tag, name in dmesh.names["boundaries"].items():
        assert dmesh.boundary_tag(name) == tag
    with pytest.raises(KeyError, match=r"no boundary named 'roof'; available: \['bottom', 'left', 'right', 'top'\]"):
        dmesh.boundary_tag("roof")
    assert dmesh.joint_tag("joint_1") == 100 and dmesh.block_tag("block_2") == 2


def test_coupling_rejects_a_bad_range_option(dmesh):
    V = case.problem(dmesh, case.LONG).coupling.V
    with pytest.raises(ValueError, match="beyond_range"):
        JointCoupling(V, dmesh, {"joint_1": case.LONG}, beyond_range=True)


def test_the_range_is_read_through_behaviours_and_hysteresis():
    """The words name the table's own last knot (Barton-Bandis closed form: Δ(2 MPa) = 0.1667 mm)
    whether the table comes bare, in a JointBehaviour or as a hysteretic law's virgin curve."""
    words = "its table covers σ_n 0 - 2 MPa (closure up to 0.1667 mm)"
    assert round(case.law_closure(2e6) * 1e3, 4) == 0.1667
    hysteretic = rockjoint.NormalHysteresis(case.SHORT, 0.3, 2.0)
    behaviour = joint_behaviours({"j": 1}, {"j": hysteretic}, shear_stiffness=1e9)[1]
    for law in (case.SHORT, hysteretic, behaviour):
        assert law_range(law)[0] == words
        assert "linear continuation" in law_range(law)[1]
    # a law with a finite maximum closure and σ = inf there: the closure only
    assert law_range(rockjoint.ExponentialLaw(1e-3, 1e6))[0] == "its law (exponential) is valid below closure 1 mm"


def test_smeared_sets_past_their_table_warn_by_the_same_check(dmesh):
    """JointedRockModel(continuum=...): a horizontal set smeared in the lower block, its table to
    2 MPa, under the uniaxial 10 MPa (σ_n = 10 MPa on the set, closed form): the stage warns for the
    smeared set as for the discrete joint, from the set's law status at its closure."""
    bed = joint_behaviours({"bed": 0}, {"bed": case.SHORT}, shear_stiffness=1e9)[0]
    model = JointedRockModel(dmesh, rock=(case.E, case.NU), joints={"joint_1": case.LONG}, shear_stiffness=1e9,
                             plane="strain", newton=NewtonOptions(verbose=False),
                             continuum={"block_1": EquivalentContinuum(2, case.E, case.NU,
                                                                      [JointSet([0.0, 1.0], 0.5, bed, label="bed")])})
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -case.LOAD))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        model.solve(name="load")
    (message,) = range_warnings(record)   # the discrete joint's LONG table covers the load
    assert "in stage 'load' (smeared joint sets): joint 'bed':" in message, message
    assert "σ_n reaches 10 MPa where its table covers σ_n 0 - 2 MPa" in message, message
