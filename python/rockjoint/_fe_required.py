# SPDX-License-Identifier: MIT
"""Whether the FE stack (DOLFINx and the compiled rockjoint._rockjoint_fem_coupling) must be there.

Under CI (the CI variable set, as every CI service does) or with ROCKJOINT_REQUIRE_FE=1 a missing
or broken FE stack is an error, never something quietly left out: otherwise a broken extension
turns the whole FE test suite into skips and the run stays green (issue 30). No DOLFINx import
here, so anything can ask."""
import os


def fe_required() -> bool:
    """True if the FE layer must be there: under CI (CI set, not 0/false/no) or with
    ROCKJOINT_REQUIRE_FE=1; then a missing FE extension is an error, never a skip (issue 30)."""
    ci = os.environ.get("CI", "").strip().lower()
    return ci not in ("", "0", "false", "no") or os.environ.get("ROCKJOINT_REQUIRE_FE", "") == "1"
