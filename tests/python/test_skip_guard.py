# SPDX-License-Identifier: MIT
"""The skip guard (skip_guard.py, fe_stack.py) does what CI relies on: under ROCKJOINT_REQUIRE_FE=1
a skipped test fails the session and a missing module is an error naming it; outside CI the same
skip is a skip; every run prints its skip count. Each case is a pytest run of its own."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

SKIPPING = "import pytest\n\ndef test_passes():\n    pass\n\ndef test_skips():\n    pytest.skip('no reason')\n"
MISSING = ("from fe_stack import require\nrequire('rockjoint_no_such_module')\n\n"
           "def test_never_collected():\n    pass\n")


def run(tmp_path, text, require_fe):
    (tmp_path / "test_case.py").write_text(text)
    env = {k: v for k, v in os.environ.items() if k not in ("CI", "ROCKJOINT_REQUIRE_FE")}
    env["PYTHONPATH"] = os.pathsep.join([HERE] + [p for p in sys.path if p])
    if require_fe:
        env["ROCKJOINT_REQUIRE_FE"] = "1"
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "--color=no", "-p", "skip_guard",
                        "-p", "no:cacheprovider", "-c", os.devnull, "--rootdir", str(tmp_path),
                        str(tmp_path / "test_case.py")],
                       capture_output=True, text=True, env=env, timeout=120)
    return r.returncode, r.stdout + r.stderr


def test_a_skip_fails_the_session_when_the_fe_stack_is_required(tmp_path):
    code, out = run(tmp_path, SKIPPING, require_fe=True)
    assert code == 1, out
    assert "rockjoint: 1 skipped (CI / ROCKJOINT_REQUIRE_FE=1" in out
    assert "SKIP NOT ALLOWED" in out and "test_skips" in out and "session FAILED" in out


def test_a_skip_is_a_skip_outside_ci(tmp_path):
    code, out = run(tmp_path, SKIPPING, require_fe=False)
    assert code == 0, out
    assert "rockjoint: 1 skipped (skips allowed outside CI" in out and "SKIP NOT ALLOWED" not in out


def test_a_missing_module_is_an_error_naming_it_when_required(tmp_path):
    code, out = run(tmp_path, MISSING, require_fe=True)
    assert code != 0, out
    assert "rockjoint_no_such_module does not import" in out and "ROCKJOINT_REQUIRE_FE=1" in out
    code, out = run(tmp_path, MISSING, require_fe=False)
    # (exit code 5: the only module skipped, pytest collected no test; not a failure)
    assert code == 5 and "rockjoint: 1 skipped" in out, out
