# SPDX-License-Identifier: MIT
"""Shared pytest configuration: the `mpi` marker selects tests meant for `mpirun -n 2`; a
DeprecationWarning is an error (the code uses DOLFINx 0.11's current API, not its deprecated
routes, and 0.9 is adapted in rockjoint.fem.compat). The skip guard, which prints the
skip count and fails a CI / ROCKJOINT_REQUIRE_FE=1 session on any skip not allowed there, is
loaded by the repository's top-level conftest.py (pytest accepts plugins only there)."""


def pytest_configure(config):
    config.addinivalue_line("markers", "mpi: run under mpirun -n 2 (registered as its own ctest)")
    config.addinivalue_line("filterwarnings", "error::DeprecationWarning")
    config.addinivalue_line("filterwarnings", "error::PendingDeprecationWarning")
