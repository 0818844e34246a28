# SPDX-License-Identifier: MIT
"""A user's first command works (issue 39, item 3): `python3 -m pytest` and
`python3 -m pytest tests/python` from the repository root, with no PYTHONPATH, collect the same
serial suite that ctest's pytest_serial runs (the repository's pytest.ini and top-level
conftest.py: the skip guard is a plugin there, since pytest refuses plugins in a nested conftest)."""
import os
import re
import subprocess
import sys

import rockjoint

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
HERE = os.path.dirname(os.path.abspath(__file__))
#: the build tree whose extension modules this run imports (build/ or build-0.9/)
BUILD = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(rockjoint._rockjoint.__file__))))


def collect(*args, cwd=ROOT):
    """(exit code, number of tests collected, output) of a `pytest --collect-only` run."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["ROCKJOINT_BUILD_DIR"] = BUILD
    r = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "--color=no", *args],
                       cwd=cwd, capture_output=True, text=True, env=env, timeout=600)
    out = r.stdout + r.stderr
    found = re.search(r"(\d+)(?:/\d+)? tests? (?:collected|selected)", out)
    return r.returncode, int(found.group(1)) if found else 0, out


def test_pytest_from_the_root_collects_the_serial_suite():
    code, n_root, out = collect()
    assert code == 0, out
    assert "pytest_plugins" not in out, out
    code, n_tests, out_tests = collect("tests/python")
    assert code == 0, out_tests
    # the same suite both ways, as ctest runs it (its own arguments, from the build tree)
    code, n_ctest, out_ctest = collect("-m", "not mpi", "-p", "no:cacheprovider", HERE,
                                       cwd=BUILD)
    assert code == 0, out_ctest
    assert n_root == n_tests == n_ctest, (n_root, n_tests, n_ctest)
    assert n_root > 200      # the whole serial suite, not a stray file's tests
    assert "test_pytest_from_root.py" in out and "test_fem_column.py" in out
