# SPDX-License-Identifier: MIT
"""pytest plugin (loaded by conftest.py): every run prints its skip count, and under CI or
ROCKJOINT_REQUIRE_FE=1 (ctest sets it) a skip not in ALLOWED_SKIPS fails the session.

A skip is how a broken FE layer or an API change used to hide behind a green run (issue 30);
there the whole suite must run. Outside CI skips stay skips (a developer without DOLFINx)."""
import pytest

from rockjoint._fe_required import fe_required

#: {test id prefix: why skipping it is right even in CI}. Empty: nothing is allowed to skip.
ALLOWED_SKIPS: dict = {}

_skips = []   # (test or module id, reason)


def _record(report):
    if report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        _skips.append((report.nodeid, reason))


def pytest_collectreport(report):
    _record(report)


def pytest_runtest_logreport(report):
    if report.when in ("setup", "call"):
        _record(report)


def _allowed(nodeid):
    return next((why for prefix, why in ALLOWED_SKIPS.items() if nodeid.startswith(prefix)), None)


def _refused():
    return [(n, r) for n, r in _skips if _allowed(n) is None] if fe_required() else []


def pytest_sessionfinish(session, exitstatus):
    if _refused() and exitstatus == pytest.ExitCode.OK:
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


def pytest_terminal_summary(terminalreporter):
    tr = terminalreporter
    allowed = [(n, r) for n, r in _skips if _allowed(n) is not None]
    refused = _refused()
    mode = "CI / ROCKJOINT_REQUIRE_FE=1" if fe_required() else "skips allowed outside CI"
    tr.write_line(f"rockjoint: {len(_skips)} skipped ({mode}; allow-list: "
                  f"{len(ALLOWED_SKIPS)} entr{'y' if len(ALLOWED_SKIPS) == 1 else 'ies'})")
    for nodeid, reason in allowed:
        tr.write_line(f"  allowed skip {nodeid}: {reason} ({_allowed(nodeid)})")
    for nodeid, reason in refused:
        tr.write_line(f"  SKIP NOT ALLOWED {nodeid}: {reason}", red=True)
    if refused:
        tr.write_line(f"rockjoint: session FAILED: {len(refused)} skip(s) under CI / "
                      f"ROCKJOINT_REQUIRE_FE=1 (a missing FE stack or an API change must fail, "
                      f"not skip; allow a skip only in tests/python/skip_guard.py with a reason)",
                      red=True)
