# SPDX-License-Identifier: MIT
"""Checks of the user's PETSc options (DOLFINx convention: {option: value} without the leading
dash, under an options prefix), shared by JointedRockModel and JointedNonlinearProblem.snes_solver."""
from __future__ import annotations

from typing import Mapping


def check_petsc_options(options) -> dict:
    """{option: value} from None or a dict whose keys are option names without the leading dash."""
    if options is not None and not isinstance(options, Mapping):
        raise ValueError(f"petsc_options must be a dict {{option: value}}, got {type(options).__name__}")
    for key in options or {}:
        if not isinstance(key, str) or key.startswith("-") or not key:
            raise ValueError(f"petsc_options key {key!r}: give option names without the leading dash, "
                             f"e.g. 'ksp_type'")
    return dict(options or {})


def check_options_prefix(prefix: str | None) -> str | None:
    """None (a default prefix of the caller's) or a prefix string without a leading dash."""
    if prefix is not None and (not isinstance(prefix, str) or prefix.startswith("-")):
        raise ValueError(f"options_prefix {prefix!r}: a string without a leading dash")
    return prefix
