# SPDX-License-Identifier: MIT
"""No PETSc option is left unused (issue 30, item 7): a user's script that builds and solves
models (direct and iterative linear solvers, and solvers built but never used) ends without
PETSc's "options you set that were not used" warning, and the linear solver leaves nothing of
its own in the global options database. A control run that sets an option nobody reads shows
that the warning would be seen. (ctest also fails a pytest run whose output has the warning.)"""
import os
import subprocess
import sys

from fe_stack import require_fe

require_fe()

from petsc4py import PETSc  # noqa: E402

from rockjoint.fem.solvers.linear_solver import LinearSolver  # noqa: E402

WARNING = "options you set that were not used"
HERE = os.path.dirname(os.path.abspath(__file__))

SCRIPT = """
import sys
from petsc4py import PETSc
import rockjoint
from rockjoint.fem.solvers.linear_solver import LinearSolver
from test_fem_column import column_model
for kind in ("direct", "iterative"):
    model = column_model(2, rockjoint.BartonBandis(1e10, 1e-3), linear_solver=kind)
    model.add_traction("top", (0.0, -5e6))
    model.solve(load_steps=1)
for kind in ("direct", "iterative"):   # built, never used
    LinearSolver(PETSc.COMM_WORLD, kind, gdim=2)
if sys.argv[1:] == ["control"]:
    PETSc.Options()["rockjoint_control_option_nobody_reads"] = 1
print("solved")
"""


def run_script(*args):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([HERE] + [p for p in sys.path if p]))
    r = subprocess.run([sys.executable, "-c", SCRIPT, *args], capture_output=True, text=True,
                       env=env, timeout=300)
    return r.returncode, r.stdout + r.stderr


def test_a_script_building_models_ends_without_the_unused_options_warning():
    code, out = run_script()
    assert code == 0 and "solved" in out, out
    assert WARNING not in out, out


def test_the_warning_is_seen_when_an_option_is_left_unused():
    code, out = run_script("control")
    assert code == 0 and "solved" in out, out
    assert WARNING in out and "rockjoint_control_option_nobody_reads" in out, out


def test_the_linear_solver_leaves_nothing_of_its_own_in_the_options_database():
    before = set(PETSc.Options().getAll())
    solvers = [LinearSolver(PETSc.COMM_SELF, kind, gdim=2) for kind in ("direct", "iterative")]
    assert set(PETSc.Options().getAll()) == before
    # A user's option is the user's: kept (PETSc may read it again at a later set-up).
    user = LinearSolver(PETSc.COMM_SELF, "iterative", gdim=2, prefix="rockjoint_user_test_",
                        options={"pc_gamg_threshold": 0.05})
    assert PETSc.Options().getAll().get("rockjoint_user_test_pc_gamg_threshold") == "0.05"
    PETSc.Options().delValue("rockjoint_user_test_pc_gamg_threshold")
    for s in solvers + [user]:
        s.ksp.destroy()
