# SPDX-License-Identifier: MIT
"""docs/user-model.md on 2 ranks (mpirun -n 2 ... -m mpi): every block of the page, in order,
run on both ranks as a user's `mpirun -n 2 python3 page.py` would (test_user_model_doc builds
the script), with the page's own checks; the joint summary the page prints is the same on both
ranks and equals the serial one of the same page (issue 39: each rank printed its own maximum)."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import gmsh  # noqa: E402

from mpi_ranks import two_ranks  # noqa: E402
from test_user_model_doc import page_script  # noqa: E402


@pytest.mark.mpi
def test_the_page_runs_on_two_ranks_and_its_summary_is_the_serial_one():
    comm = two_ranks()
    parallel = {}
    exec(compile(page_script(), "docs/user-model.md", "exec"), parallel)
    fault = parallel["fault"]
    assert comm.allgather(fault) == [fault, fault]
    local = parallel["coupling"].state(parallel["u"])["closure"].size
    assert min(comm.allgather(local)) > 0, "both ranks hold joint points"
    serial = {}
    if comm.rank == 0:   # the page on one rank (its gmsh model is built on rank 0 of its comm)
        gmsh.finalize()  # the page starts gmsh afresh
        exec(compile(page_script().replace("MPI.COMM_WORLD", "MPI.COMM_SELF"), "docs/user-model.md", "exec"), serial)
    reference = comm.bcast(serial.get("fault"), root=0)
    assert (fault.points, fault.status) == (reference.points, reference.status)
    assert fault.max_closure == pytest.approx(reference.max_closure, rel=1e-8)
    assert fault.max_normal_stress == pytest.approx(reference.max_normal_stress, rel=1e-8)
