# SPDX-License-Identifier: MIT
"""The version in one place (issue 42, item 4): CMakeLists.txt's project(rockjoint VERSION x.y.z)
is rockjoint.__version__ (through the compiled module) and what `python3 -m rockjoint --version`
prints; the changelog names it."""
import os
import re
import subprocess
import sys

import rockjoint

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def project_version() -> str:
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as fh:
        return re.search(r"^project\(rockjoint VERSION ([0-9.]+)", fh.read(), re.M).group(1)


def test_the_package_version_is_the_project_version():
    assert re.fullmatch(r"\d+\.\d+\.\d+", rockjoint.__version__)
    assert rockjoint.__version__ == project_version()


def test_the_command_line_prints_it():
    r = subprocess.run([sys.executable, "-m", "rockjoint", "--version"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == f"rockjoint {project_version()}"


def test_the_changelog_names_it():
    with open(os.path.join(ROOT, "CHANGELOG.md"), encoding="utf-8") as fh:
        assert f"({project_version()} development)" in fh.read()
