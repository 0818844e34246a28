# SPDX-License-Identifier: MIT
"""Console output of scripts that run serially or under mpirun (the demos): rank 0 speaks.

DOLFINx compiles forms on first use through setuptools, which sets the root logger to INFO and
would print every compiler command: `quiet_compiler_logging()` lets only warnings through the
root logger's handlers. A script's own progress goes through its own logger or `say`.
"""
from __future__ import annotations

import logging
import sys
import warnings


def quiet_compiler_logging() -> None:
    """Root logger: warnings and errors only (on every handler, the ones DOLFINx added too)."""
    logging.basicConfig(level=logging.WARNING)
    for handler in logging.getLogger().handlers:
        handler.setLevel(logging.WARNING)


def rank_logger(name: str, comm=None) -> logging.Logger:
    """The logger of a script run serially or under mpirun (the demos): its messages bare, on
    standard error, at INFO on rank 0 of `comm` (default MPI.COMM_WORLD) and warnings only on
    the others; not passed on to the root logger (quiet_compiler_logging keeps that at warnings)."""
    if comm is None:
        from mpi4py import MPI  # optional (the FE stack): only when no communicator is given
        comm = MPI.COMM_WORLD
    log = logging.getLogger(name)
    log.propagate = False
    if not log.handlers:
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("%(message)s"))
        log.addHandler(handler)
    log.setLevel(logging.INFO if comm.rank == 0 else logging.WARNING)
    return log


def say(*args, comm=None) -> None:
    """``print(*args)`` on rank 0 of `comm` (default MPI.COMM_WORLD), flushed."""
    if comm is None:
        from mpi4py import MPI  # optional (the FE stack): only when no communicator is given
        comm = MPI.COMM_WORLD
    if comm.rank == 0:
        print(*args, flush=True)


def warnings_as_lines() -> None:
    """Show Python warnings (a law driven past its table: rockjoint.fem.RangeWarning) as one line
    each, "warning: <message>", on standard error: what a command-line user reads, without the
    file and source line of the code that raised it. Also when a library routes warnings into
    logging later (logging.captureWarnings, as DOLFINx 0.9's import does): the formatted warning
    is then the message alone, and the "py.warnings" logger prints it the same way."""
    def show(message, category, filename, lineno, file=None, line=None):
        print(f"warning: {message}", file=file or sys.stderr, flush=True)
    warnings.showwarning = show
    warnings.formatwarning = lambda message, category, filename, lineno, line=None: str(message)
    captured = logging.getLogger("py.warnings")
    if not captured.handlers:
        handler = logging.StreamHandler(sys.stderr)
        handler.setFormatter(logging.Formatter("warning: %(message)s"))
        captured.addHandler(handler)
    captured.propagate = False
