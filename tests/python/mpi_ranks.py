# SPDX-License-Identifier: MIT
"""The rank check shared by the `mpi`-marked tests (tests/python/test_*mpi*.py), which ctest runs
under `mpirun -n 2`."""
from mpi4py import MPI


def two_ranks(comm=MPI.COMM_WORLD):
    """`comm`, after checking that it has the 2 ranks the test is written for."""
    assert comm.size == 2, "run with mpirun -n 2"
    return comm
