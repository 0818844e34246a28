# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint topography analyse upper lower` on scans: STL and XYZ point clouds in
their scanners' frames are registered (format by extension or --format), the registration and
its residual misfit reach the JSON; bad files give a one-line error naming file and line."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import scan_cases as sc
from rockjoint import scans


def _cli(*args):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    env.setdefault("MPLBACKEND", "Agg")
    return subprocess.run([sys.executable, "-m", "rockjoint", "topography", *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=300)


@pytest.mark.parametrize("kind", ["stl", "points"])
def test_cli_registers_scans_and_reports_the_misfit(tmp_path, kind):
    truth = sc.joint(seed=3, matedness=0.0)
    rng = np.random.default_rng(8)
    low_frame = sc.rigid(30.0, [0.1, -0.05, 0.02])
    up_frame = sc.rigid(-20.0, [0.3, 0.2, -0.1]) @ sc.FLIP
    low, low_xy = sc.scan_wall(truth.lower, (2e-3, 46e-3, 2e-3, 46e-3), 0.4e-3, jitter=0.08e-3,
                               noise=2e-6, hole=None, frame=low_frame, rng=rng)
    up, up_xy = sc.scan_wall(truth.upper, (6e-3, 42e-3, 4e-3, 44e-3), 0.4e-3, jitter=0.08e-3,
                             noise=2e-6, hole=None, frame=up_frame, gap=truth.gap, rng=rng)
    if kind == "stl":
        files = [scans.write_stl(tmp_path / "upper.stl", up, sc.mesh_without_hole(up, up_xy,
                                                                             (0, 0, 0))),
                 scans.write_stl(tmp_path / "lower.stl", low, sc.mesh_without_hole(low, low_xy,
                                                                              (0, 0, 0)))]
        extra = []
    else:
        files = [scans.write_xyz_points(tmp_path / "upper.xyz", up),
                 scans.write_xyz_points(tmp_path / "lower.xyz", low)]
        extra = ["--format", "points"]
    r = _cli("analyse", *files, *extra, "--spacing", 0.4, "--fill", "refuse",
             "--json", tmp_path / "p.json")
    assert r.returncode == 0, r.stderr
    assert "residual misfit" in r.stdout
    report = json.loads((tmp_path / "p.json").read_text())
    assert report["registration"]["rotation_deg"] == pytest.approx(10.0, abs=0.05)
    assert report["registration"]["hole_nodes"] == 0
    assert report["sampling_interval_mm"] == pytest.approx(0.4)
    # identical walls: the aperture varies by the resampling error only (µm, not 0.1 mm)
    assert report["registration"]["residual_misfit_mm"] < 0.005


def test_cli_reports_a_bad_scan_cleanly(tmp_path):
    p = tmp_path / "bad.stl"
    p.write_bytes(b"x" * 80 + (10).to_bytes(4, "little") + b"\0" * 120)
    r = _cli("analyse", p, p)
    assert r.returncode == 1
    assert f"{p}: facet 2: binary STL header announces 10 facets" in r.stderr
    assert "Traceback" not in r.stderr


def test_cli_unstructured_xyz_without_format_points_says_so(tmp_path):
    p = tmp_path / "cloud.xyz"
    rng = np.random.default_rng(1)
    xy = rng.uniform(0, 20, (400, 2))
    np.savetxt(p, np.column_stack([xy, 0.01 * xy[:, 0]]),
               header="lateral_unit: mm\nheight_unit: mm", comments="# ")
    r = _cli("analyse", p)
    assert r.returncode == 1
    assert "use --format points" in r.stderr and "Traceback" not in r.stderr
    r = _cli("analyse", p, "--format", "points")
    assert r.returncode == 0, r.stderr
    assert "levelled on its mean plane" in r.stdout
