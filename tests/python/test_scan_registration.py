# SPDX-License-Identifier: MIT
"""Two walls scanned in their own frames (STL binary and ASCII, XYZ point cloud, ESRI grid),
with a rigid motion (rotation about z and a 3D offset; for "xyz-tilted" also 4° and -7°
tilts of the scanners), the upper one seen from the other side, noise and a hole: the recovered aperture must match the known one to within the
resampling error bound of rockjoint.scans.lattice, and the registration must recover the
relative motion.

Tolerance (per node, after removing a plane: the relative tilt of separately scanned walls
is not in the data and the composite's plane removal takes it out):
    R²/2 (M_u + M_l)            linear interpolation on the samples' triangles (Waldron 1998),
                                R the largest enclosing radius, M the walls' max |∂²z/∂u²|
  + 2a                          uniform measurement noise ±a on each wall
  + G (δ + Z (t_u + t_l))       G the walls' slope bound, δ the measured misregistration of
                                the upper samples, Z the walls' height span and t the tilt
                                of each levelled frame (a lateral shift of z·t)
All of R, M, G, δ, Z, t come from the synthetic truth (scan_cases), not from the code."""
import numpy as np
import pytest

import scan_cases as sc
from rockjoint import scans
from rockjoint.scans.frame import flip

STEP = 0.4e-3                     # scanner sample spacing [m]
NOISE = 2e-6                      # ±2 µm
LOWER_REGION = (2e-3, 46e-3, 2e-3, 46e-3)
UPPER_REGION = (6e-3, 42e-3, 4e-3, 44e-3)
HOLE = (20e-3, 25e-3, 3e-3)       # a 3 mm dropout on the lower wall
LOWER_FRAME = sc.rigid(30.0, [0.1, -0.05, 0.02])
UPPER_FRAME = sc.rigid(-20.0, [0.3, 0.2, -0.1]) @ sc.FLIP
RELATIVE_ROTATION = 10.0          # [deg]: flip(R(-20°)) = R(+20°); lower R(30°)
# an ESRI grid is in its scanner's own coordinates, e.g. metres off the lab origin
ESRI_LOWER_FRAME = sc.rigid(30.0, [1.0, 2.0, 0.005])
ESRI_UPPER_FRAME = sc.rigid(-20.0, [-0.3, 0.5, -0.01]) @ sc.FLIP
# scanners whose tables are not level: the levelling must take the 4° and 7° out
TILTED_LOWER_FRAME = LOWER_FRAME @ sc.tilt_about_x(4.0)
TILTED_UPPER_FRAME = sc.rigid(-20.0, [0.3, 0.2, -0.1]) @ sc.tilt_about_x(-7.0) @ sc.FLIP
MATEDNESS = 5e-3                  # shared wavelengths >= 5 mm, independent 4-5 mm


@pytest.fixture(scope="module")
def truth():
    return sc.joint(seed=3, matedness=MATEDNESS)


def _frames(kind):
    if kind == "esri":
        return ESRI_LOWER_FRAME, ESRI_UPPER_FRAME
    if kind == "xyz-tilted":
        return TILTED_LOWER_FRAME, TILTED_UPPER_FRAME
    return LOWER_FRAME, UPPER_FRAME


def _point_scans(truth, rng, frames=(LOWER_FRAME, UPPER_FRAME)):
    low, low_xy = sc.scan_wall(truth.lower, LOWER_REGION, STEP, jitter=0.2 * STEP,
                               noise=NOISE, hole=HOLE, frame=frames[0], rng=rng)
    up, up_xy = sc.scan_wall(truth.upper, UPPER_REGION, STEP, jitter=0.2 * STEP, noise=NOISE,
                             hole=None, frame=frames[1], gap=truth.gap, rng=rng)
    return low, low_xy, up, up_xy


def _write(tmp_path, kind, truth, rng):
    """Both walls written in format ``kind``; returns the paths and the joint-frame (x, y)
    of the samples each file holds."""
    if kind == "esri":
        # each scanner's grid: 36 mm (lower) and 32 mm (upper) squares over the joint centre
        paths, xys = [], []
        for name, wall, frame, n, hole, gap in (
                ("lower", truth.lower, ESRI_LOWER_FRAME, 90, HOLE, 0.0),
                ("upper", truth.upper, ESRI_UPPER_FRAME, 80, None, truth.gap)):
            origin = sc.apply(frame, np.array([[24e-3, 24e-3, 0.0]]))[0, :2] - STEP * n / 2
            h, xy = sc.scan_grid(wall, frame, origin, (n, n), STEP, noise=NOISE, hole=hole,
                                 gap=gap, rng=rng)
            grid = scans.ScanGrid(h, STEP, STEP, tuple(origin))
            paths.append(scans.write_esri_ascii(tmp_path / f"{name}.asc", grid,
                                                centre=name == "upper"))
            xys.append(xy)
        return paths[0], xys[0], paths[1], xys[1]
    low, low_xy, up, up_xy = _point_scans(truth, rng, _frames(kind))
    if kind in ("xyz", "xyz-tilted"):
        return (scans.write_xyz_points(tmp_path / "lower.xyz", low), low_xy,
                scans.write_xyz_points(tmp_path / "upper.csv", up), up_xy)
    binary = kind == "stl-binary"
    paths = []
    for name, p, xy, hole in (("lower", low, low_xy, HOLE), ("upper", up, up_xy, (0, 0, 0))):
        tri = sc.mesh_without_hole(p, xy, hole)
        paths.append(scans.write_stl(tmp_path / f"{name}.stl", p, tri, binary=binary))
    return paths[0], low_xy, paths[1], up_xy


def _box(xy):
    return (xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max())


def _misregistration(joint, truth, upper_xy, frames=(LOWER_FRAME, UPPER_FRAME)) -> float:
    """Max in-plane distance [m] between where the pipeline puts each upper sample in the
    joint frame and where it truly is."""
    z = truth.upper(upper_xy[:, 0], upper_xy[:, 1]) + truth.gap
    upper_points = sc.apply(frames[1], np.column_stack([upper_xy, z]))
    lev = joint.upper_levelling
    q = joint.registration.apply((flip(upper_points) - lev.centroid) @ lev.rotation.T)
    q[:, 2] = 0.0
    pj = sc.apply(np.linalg.inv(frames[0]), joint.lower_levelling.to_scanner(q))
    return float(np.max(np.hypot(*(pj[:, :2] - upper_xy).T)))


def _aperture_error(joint, truth, lower_frame):
    """Recovered aperture (the composite's, after plane removal and first-contact shift)
    minus the true one at the same joint-frame points, less its least-squares plane."""
    nodes = sc.apply(np.linalg.inv(lower_frame), joint.scanner_coordinates().reshape(-1, 3))
    e = joint.composite.aperture.heights.ravel()
    d = e - truth.aperture(nodes[:, 0], nodes[:, 1])
    ok = np.isfinite(d)
    a = np.column_stack([nodes[ok, 0], nodes[ok, 1], np.ones(ok.sum())])
    return d[ok] - a @ np.linalg.lstsq(a, d[ok], rcond=None)[0], int(np.count_nonzero(~ok))


@pytest.mark.parametrize("matedness", [0.0, MATEDNESS])
@pytest.mark.parametrize("kind", ["stl-binary", "stl-ascii", "xyz", "xyz-tilted", "esri"])
def test_recovered_aperture_matches_the_known_one_within_the_resampling_bound(tmp_path, kind,
                                                                             matedness):
    """Identical walls (λ_m = 0) have one best registration, the true one: it must be found to
    1/8 of the sample spacing. Partially mated walls (λ_m = 5 mm) are registered where they are
    most mated, which differs from where they were generated by the chance fit of the unmated
    4-5 mm roughness (measured: up to 0.25° over a 32 mm patch, the recovered position has the
    lower misfit): required within one sample spacing, and the measured δ enters the bound."""
    truth = sc.joint(seed=3, matedness=matedness)
    rng = np.random.default_rng(11)
    low_path, low_xy, up_path, up_xy = _write(tmp_path, kind, truth, rng)
    upper, lower = scans.read_scan(up_path), scans.read_scan(low_path)
    joint = scans.joint_from_scans(upper, lower, fill="none")

    frames = _frames(kind)
    delta = _misregistration(joint, truth, up_xy, frames)
    limit = STEP / 8 if matedness == 0 else STEP
    assert delta <= limit, f"registration off by {delta * 1e6:.1f} µm (> {limit * 1e6:.0f} µm)"
    if kind != "xyz-tilted":   # with tilts the in-plane angle is not simply 10°: δ says it
        rotation = np.degrees(joint.registration.rotation)
        assert abs(rotation - RELATIVE_ROTATION) < (0.05 if matedness == 0 else 0.5), rotation

    region = (0.0, 48e-3, 0.0, 48e-3)
    step = sc.SPEC.cutoff_wavelength / 16
    m = truth.upper.max_second_derivative(region, step) + \
        truth.lower.max_second_derivative(region, step)
    r = max(sc.max_enclosing_radius(low_xy), sc.max_enclosing_radius(up_xy))
    g = max(truth.upper.max_slope(region, step), truth.lower.max_slope(region, step))
    span = 2 * max(np.ptp(truth.upper(up_xy[:, 0], up_xy[:, 1])),
                   np.ptp(truth.lower(low_xy[:, 0], low_xy[:, 1])))
    tilt = sc.plane_tilt(truth.upper, _box(up_xy)) + sc.plane_tilt(truth.lower, _box(low_xy))
    bound = r * r / 2 * m + 2 * NOISE + g * (delta + span * tilt)
    err, holes = _aperture_error(joint, truth, frames[0])
    assert np.max(np.abs(err)) <= bound, (
        f"aperture error {np.max(np.abs(err)) * 1e6:.2f} µm > resampling bound "
        f"{bound * 1e6:.2f} µm (R {r * 1e3:.3f} mm, M {m:.4g} 1/m, δ {delta * 1e6:.2f} µm)")
    # the dropout is inside the overlap: flagged, counted, and left masked (fill="none")
    assert holes == joint.masked_count > 0
    if matedness > 0:  # residual misfit = the unmated 4-5 mm roughness, >> resampling error
        assert joint.registration.residual_rms > 5 * np.std(err)


def test_identical_walls_register_to_a_flat_aperture(tmp_path):
    """Perfectly mated walls (λ_m = 0): the residual misfit is the resampling error only."""
    truth = sc.joint(seed=5, matedness=0.0)
    rng = np.random.default_rng(2)
    low, low_xy, up, up_xy = _point_scans(truth, rng)
    joint = scans.joint_from_scans(scans.ScanPoints(up), scans.ScanPoints(low))
    assert _misregistration(joint, truth, up_xy) <= STEP / 8
    region = (0.0, 48e-3, 0.0, 48e-3)
    m = 2 * truth.lower.max_second_derivative(region, sc.SPEC.cutoff_wavelength / 16)
    r = max(sc.max_enclosing_radius(low_xy), sc.max_enclosing_radius(up_xy))
    assert joint.registration.residual_rms <= r * r / 2 * m + 2 * NOISE


def test_walls_that_do_not_overlap_are_refused(truth):
    """Scans of two different joints (independent walls) match nowhere: no overlap of mated
    topography, refused instead of registered at a chance correlation."""
    other = sc.joint(seed=99, matedness=MATEDNESS)
    rng = np.random.default_rng(4)
    low, _ = sc.scan_wall(truth.lower, LOWER_REGION, STEP, jitter=0.0, noise=0.0, hole=None,
                          frame=np.eye(4), rng=rng)
    up, _ = sc.scan_wall(other.upper, UPPER_REGION, STEP, jitter=0.0, noise=0.0, hole=None,
                         frame=sc.FLIP, rng=rng)
    with pytest.raises(scans.NoOverlapError, match=r"u\.xyz: the walls do not match"):
        scans.joint_from_scans(scans.ScanPoints(up, "u.xyz"), scans.ScanPoints(low, "l.xyz"))
