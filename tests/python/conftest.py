"""Shared pytest configuration: the `mpi` marker selects tests meant for `mpirun -n 2`."""


def pytest_configure(config):
    config.addinivalue_line("markers", "mpi: run under mpirun -n 2 (registered as its own ctest)")
