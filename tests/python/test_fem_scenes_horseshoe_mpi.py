# SPDX-License-Identifier: MIT
"""Issue 40: the horseshoe tunnel scene (demos/scenes/tunnel_horseshoe.yaml, reduced) on 2 ranks
gives the serial answer: run on MPI.COMM_WORLD (2 ranks) and on COMM_SELF (each rank alone), the
monitored opening displacements, slipping points and largest closure equal to solver tolerance."""
import os

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()
from mpi4py import MPI  # noqa: E402

from mpi_ranks import two_ranks  # noqa: E402
from rockjoint.scenes import load_scene, make_plan, run_scene  # noqa: E402
from scene_cases import SCENES  # noqa: E402


@pytest.mark.mpi
def test_horseshoe_scene_on_two_ranks_equals_serial(tmp_path_factory):
    comm = two_ranks()
    root = comm.bcast(str(tmp_path_factory.mktemp("scene")) if comm.rank == 0 else None)
    scene = load_scene(os.path.join(SCENES, "tunnel_horseshoe.yaml")).at_reduced_size()
    plan = make_plan(scene)
    parallel = run_scene(scene, plan, os.path.join(root, "parallel"), comm=comm)
    serial = run_scene(scene, plan, os.path.join(root, f"serial{comm.rank}"), comm=MPI.COMM_SELF)
    assert len(parallel.rows) == len(serial.rows) > 0
    for p, s in zip(parallel.rows, serial.rows):
        assert (p.model, p.stage, p.slipping) == (s.model, s.stage, s.slipping)
        np.testing.assert_allclose(p.monitors["opening"], s.monitors["opening"], rtol=1e-7, atol=1e-12)
        assert p.max_closure == pytest.approx(s.max_closure, rel=1e-7)
    # the opening converges (mean normal displacement into it > 0) and the joints add to it
    jointed, intact = parallel.row("jointed", "excavation"), parallel.row("intact", "excavation")
    assert jointed.monitors["opening"][-1] > intact.monitors["opening"][-1] > 0.0
    if comm.rank == 0:
        assert {"summary.txt", "scene.png", "jointed.xdmf", "intact.xdmf"} <= set(parallel.files)
