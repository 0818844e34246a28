# SPDX-License-Identifier: MIT
"""rockjoint.fem leaves the joint elements out only when the build has no FE extension
file (-DROCKJOINT_FEM=OFF), and then says what is missing; an extension that exists but does not
load, or any missing one under CI / ROCKJOINT_REQUIRE_FE=1, is an ImportError (issue 30: a
swallowed import error turned the FE suite into skips). Each case imports in a process of its
own, from a build folder made here: the real _rockjoint, and no or a broken FE extension."""
import glob
import os
import subprocess
import sys

import pytest

import rockjoint
from fe_stack import require

require("dolfinx")

SOURCE_PYTHON = os.path.dirname(os.path.dirname(os.path.abspath(rockjoint.__file__)))
PROBE = ("import rockjoint.fem as fc\n"
         "print('imported')\n"
         "fc.JointedRockModel\n")


def fake_build(tmp_path, extension):
    """<tmp>/rockjoint/ with the real compiled _rockjoint and `extension`: None (no FE extension
    file) or "broken" (a file of that name that is no shared library)."""
    real = [d for d in rockjoint.__path__ if glob.glob(os.path.join(d, "_rockjoint.*"))][0]
    folder = tmp_path / "rockjoint"
    folder.mkdir()
    core = glob.glob(os.path.join(real, "_rockjoint.*"))[0]
    os.symlink(core, folder / os.path.basename(core))
    for extra in ("meshes",):
        if os.path.isdir(os.path.join(real, extra)):
            os.symlink(os.path.join(real, extra), folder / extra)
    if extension == "broken":
        fem = glob.glob(os.path.join(real, "_rockjoint_fem_coupling.*"))[0]
        (folder / os.path.basename(fem)).write_text("not a shared library\n")
    return tmp_path


def probe(build, require_fe):
    others = [p for p in sys.path if p and not p.rstrip("/").endswith("python")]
    env = {k: v for k, v in os.environ.items() if k not in ("CI", "ROCKJOINT_REQUIRE_FE")}
    env["PYTHONPATH"] = os.pathsep.join([SOURCE_PYTHON, str(build)] + others)
    if require_fe:
        env["ROCKJOINT_REQUIRE_FE"] = "1"
    r = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env,
                       timeout=120)
    return r.returncode, r.stdout + r.stderr


def test_a_build_without_the_extension_imports_and_names_what_is_missing(tmp_path):
    code, out = probe(fake_build(tmp_path, None), require_fe=False)
    assert code == 1 and "imported" in out, out
    assert "AttributeError" in out and "-DROCKJOINT_FEM=ON" in out and "JointedRockModel" in out


@pytest.mark.parametrize("extension,require_fe", [(None, True), ("broken", False), ("broken", True)])
def test_a_missing_or_broken_extension_is_an_import_error(tmp_path, extension, require_fe):
    code, out = probe(fake_build(tmp_path, extension), require_fe)
    assert code == 1 and "imported" not in out, out
    assert "ImportError" in out and "_rockjoint_fem_coupling" in out, out
