# SPDX-License-Identifier: MIT
"""The one way a test asks for the FE stack (DOLFINx, the compiled FE extension) or another
optional module.

Outside CI a module that is missing skips the test (a developer without DOLFINx still runs the
rest). Under CI or ROCKJOINT_REQUIRE_FE=1 (rockjoint._fe_required; ctest sets it) it is an error
naming the module and why it does not import: a broken FE extension must fail the run, not turn
the FE suite into skips (issue 30). conftest.py also fails such a session on any skip."""
import importlib

import pytest

from rockjoint._fe_required import fe_required

FE_MODULES = ("dolfinx", "rockjoint._rockjoint_fem_coupling")


def require(name: str):
    """The module `name`: imported, skipped (outside CI) or a failure naming it (CI)."""
    if not fe_required():
        return pytest.importorskip(name)
    try:
        return importlib.import_module(name)
    except ImportError as error:
        pytest.fail(f"{name} does not import ({type(error).__name__}: {error}); CI / "
                    f"ROCKJOINT_REQUIRE_FE=1 require it (build with -DROCKJOINT_FEM=ON against "
                    f"DOLFINx, see docs/install.md)", pytrace=False)


def require_fe():
    """DOLFINx and rockjoint's FE extension (as `require`); returns the dolfinx module."""
    dolfinx = require(FE_MODULES[0])
    require(FE_MODULES[1])
    return dolfinx
