# SPDX-License-Identifier: MIT
"""The repository's top-level pytest configuration (pytest allows plugins only here).

Puts the checkout's Python package and its built extension modules on sys.path when nothing
else did (`python3 -m pytest` from the root needs no PYTHONPATH; ctest and scripts/run.sh set
it, and then nothing changes), and loads tests/python/skip_guard.py, the plugin that fails a CI
run on any skip (issue 30)."""
import os
import sys

_repo = os.path.dirname(os.path.abspath(__file__))
_build = os.environ.get("ROCKJOINT_BUILD_DIR") or os.path.join(_repo, "build")
for _path in reversed((os.path.join(_repo, "python"), os.path.join(_build, "python"),
                       os.path.join(_repo, "tests", "python"))):
    if _path not in sys.path:
        sys.path.insert(0, _path)

pytest_plugins = ["skip_guard"]
