# SPDX-License-Identifier: MIT
"""Synthetic scans with a known truth for the scan tests: a mated pair from the project's own
generator (rockjoint.topography.mated_pair), continued between its lattice nodes by its
Fourier series (the generator's walls are periodic and, with a short-wavelength cut-off,
band-limited, so the series is the surface and can be evaluated anywhere), then sampled the
way scanners sample, moved into scanner frames by known rigid motions, with noise and holes.

Bounds used by the tests come from the series, not from the code under test:
  max|∂²z/∂u²| <= Σ|c_k||k|²  (any direction u),   max|∇z| <= Σ|c_k||k|."""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import Delaunay

from rockjoint import topography as topo

H = 0.5e-3              # lattice of the generator [m]
SHAPE = (96, 96)        # 48 mm x 48 mm period
SPEC = topo.SelfAffineSpec(hurst_exponent=0.8, rms_height=0.4e-3, cutoff_wavelength=8 * H)
MATEDNESS = 8e-3        # the walls share every wavelength >= 8 mm


class FourierWall:
    """The trigonometric interpolant of a periodic lattice wall: z(x, y) anywhere [m]."""

    def __init__(self, surface):
        z = surface.heights
        rows, cols = z.shape
        c = np.fft.fft2(z) / z.size
        ky = 2 * np.pi * np.fft.fftfreq(rows, surface.spacing_y)
        kx = 2 * np.pi * np.fft.fftfreq(cols, surface.spacing_x)
        kx, ky = np.meshgrid(kx, ky)
        keep = np.abs(c) > 1e-12 * np.abs(c).max()
        # a Nyquist mode has no unique continuation between nodes: the cut-off removes it
        assert not np.any(keep & ((np.abs(kx) >= np.pi / surface.spacing_x * 0.999) |
                                  (np.abs(ky) >= np.pi / surface.spacing_y * 0.999)))
        self.c, self.kx, self.ky = c[keep], kx[keep], ky[keep]
        k = np.hypot(self.kx, self.ky)
        self.curvature_bound = float(np.sum(np.abs(self.c) * k * k))
        self.slope_bound = float(np.sum(np.abs(self.c) * k))

    def max_second_derivative(self, region, step: float) -> float:
        """max over a fine lattice of ``region`` of the largest |eigenvalue| of the Hessian,
        i.e. of |∂²z/∂u²| over directions u [1/m]. The wall has no wavelength below the
        cut-off λ_s, so a lattice of step << λ_s resolves the maximum; the tests use
        step = λ_s/64, where the Hessian changes by at most step·Σ|c_k||k|³ between nodes,
        which is added."""
        best = 0.0
        for e in self._fourier_blocks(region, step):
            hxx = -(e @ (self.c * self.kx ** 2)).real
            hyy = -(e @ (self.c * self.ky ** 2)).real
            hxy = -(e @ (self.c * self.kx * self.ky)).real
            lam = 0.5 * np.abs(hxx + hyy) + np.sqrt(0.25 * (hxx - hyy) ** 2 + hxy ** 2)
            best = max(best, float(lam.max()))
        k = np.hypot(self.kx, self.ky)
        return best + step * float(np.sum(np.abs(self.c) * k ** 3))

    def _fourier_blocks(self, region, step: float, block: int = 4096):
        """exp(i k·x) of the Fourier modes at the nodes of a fine lattice of ``region``, in
        blocks of nodes (rows: nodes, columns: modes)."""
        x, y = np.meshgrid(np.arange(region[0], region[1], step),
                           np.arange(region[2], region[3], step))
        x, y = x.ravel(), y.ravel()
        for s in range(0, x.size, block):
            yield np.exp(1j * (np.outer(x[s:s + block], self.kx) + np.outer(y[s:s + block], self.ky)))

    def max_slope(self, region, step: float) -> float:
        """max |∇z| over a fine lattice of ``region``, plus step·Σ|c_k||k|² for the change
        between nodes (an upper bound of the slope anywhere in the region)."""
        best = 0.0
        for e in self._fourier_blocks(region, step):
            gx = -(e @ (self.c * self.kx)).imag
            gy = -(e @ (self.c * self.ky)).imag
            best = max(best, float(np.hypot(gx, gy).max()))
        return best + step * self.curvature_bound

    def __call__(self, x, y):
        x, y = np.asarray(x, float), np.asarray(y, float)
        out = np.empty(x.size)
        flat_x, flat_y = x.ravel(), y.ravel()
        for s in range(0, x.size, 4096):
            phase = np.outer(flat_x[s:s + 4096], self.kx) + np.outer(flat_y[s:s + 4096], self.ky)
            out[s:s + 4096] = (np.exp(1j * phase) @ self.c).real
        return out.reshape(x.shape)


def rigid(angle_deg: float, offset) -> np.ndarray:
    """4x4 matrix of a rotation about z by angle and a 3D offset [m]."""
    a = np.radians(angle_deg)
    m = np.eye(4)
    m[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    m[:3, 3] = offset
    return m


def tilt_about_x(angle_deg: float) -> np.ndarray:
    """4x4 rotation about x: a scanner whose table is not level."""
    a = np.radians(angle_deg)
    m = np.eye(4)
    m[1:3, 1:3] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    return m


FLIP = np.diag([-1.0, 1.0, -1.0, 1.0])   # the upper scanner looks from the other side


def apply(m: np.ndarray, p: np.ndarray) -> np.ndarray:
    return p @ m[:3, :3].T + m[:3, 3]


@dataclasses.dataclass
class Joint:
    upper: FourierWall      # z_u(x, y) in the joint frame (joint face of the upper block)
    lower: FourierWall
    gap: float              # z_u - z_l offset so the walls do not interpenetrate

    def aperture(self, x, y):
        return self.upper(x, y) + self.gap - self.lower(x, y)


def joint(seed: int = 3, matedness: float = MATEDNESS) -> Joint:
    u, l = topo.mated_pair(SPEC, SHAPE, H, matedness, seed=seed)
    upper, lower = FourierWall(u), FourierWall(l)
    gap = float(np.max(l.heights - u.heights)) + 0.05e-3
    return Joint(upper, lower, gap)


def jittered_samples(x0, x1, y0, y1, step, jitter, rng):
    """Scanner samples: a lattice of ``step`` with uniform position jitter ±jitter [m]."""
    x, y = np.meshgrid(np.arange(x0, x1 + 1e-12, step), np.arange(y0, y1 + 1e-12, step))
    x = x.ravel() + rng.uniform(-jitter, jitter, x.size)
    y = y.ravel() + rng.uniform(-jitter, jitter, y.size)
    return x, y


def scan_wall(wall, region, step, *, jitter, noise, hole, frame, gap=0.0, rng):
    """Samples (N, 3) of ``wall`` (+gap) over ``region`` (x0, x1, y0, y1) [m] in the joint
    frame, heights with uniform noise ±noise, samples in the disc ``hole`` (cx, cy, r)
    removed, then moved by the 4x4 ``frame``. Returns scanner-frame points and the joint-frame
    (x, y) of each sample."""
    x, y = jittered_samples(*region, step, jitter, rng)
    if hole is not None:
        keep = np.hypot(x - hole[0], y - hole[1]) > hole[2]
        x, y = x[keep], y[keep]
    z = wall(x, y) + gap + rng.uniform(-noise, noise, x.size)
    return apply(frame, np.column_stack([x, y, z])), np.column_stack([x, y])


def mesh_without_hole(points: np.ndarray, joint_xy: np.ndarray, hole):
    """Triangles of the samples' Delaunay triangulation in the scanner plane, minus those
    spanning the hole (a scanner's mesh does not bridge a hole)."""
    tri = Delaunay(points[:, :2]).simplices
    c = joint_xy[tri]
    centre = c.mean(axis=1)
    keep = np.hypot(centre[:, 0] - hole[0], centre[:, 1] - hole[1]) > hole[2]
    edges = np.linalg.norm(c - np.roll(c, 1, axis=1), axis=2).max(axis=1)
    keep &= edges < 3 * np.median(edges)
    return tri[keep]


def max_enclosing_radius(xy: np.ndarray) -> float:
    """Largest radius of the smallest disc containing a Delaunay triangle of (N, 2) points,
    over the triangles the hole rule keeps (longest edge <= 3 median edges): the R of the
    interpolation bound R²/2·max|∂²z/∂u²| (Waldron 1998). The disc is the circumcircle of a
    non-obtuse triangle and the one on the longest edge of an obtuse one."""
    tri = Delaunay(xy)
    c = xy[tri.simplices]
    a = np.linalg.norm(c[:, 1] - c[:, 2], axis=1)
    b = np.linalg.norm(c[:, 0] - c[:, 2], axis=1)
    d = np.linalg.norm(c[:, 0] - c[:, 1], axis=1)
    u, v = c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]
    area = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    edges = np.linalg.norm(c - np.roll(c, 1, axis=1), axis=2)
    longest = edges.max(axis=1)
    keep = longest <= 3 * np.median(edges)
    sq = np.sort(np.column_stack([a, b, d]) ** 2, axis=1)
    obtuse = sq[:, 2] >= sq[:, 0] + sq[:, 1]
    radius = np.where(obtuse, longest / 2, a * b * d / (4 * np.maximum(area, 1e-300)))
    return float(np.max(radius[keep]))


def scan_grid(wall, frame, origin, shape, step, *, noise, hole, gap=0.0, rng):
    """A scanner's own lattice (ESRI grid): nodes (origin + step·(j, i)) in the scanner frame,
    whose frame is ``frame`` (rotation about z and offset, possibly flipped, never tilted, so
    the scanner's z is ±the joint's z). Heights [m] in the scanner frame with noise, NaN in
    the hole (joint-frame disc). Returns (heights, joint-frame (x, y) of the valid nodes)."""
    xs, ys = np.meshgrid(origin[0] + step * np.arange(shape[1]),
                         origin[1] + step * np.arange(shape[0]))
    inv = np.linalg.inv(frame)
    pj = apply(inv, np.column_stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)]))
    z = wall(pj[:, 0], pj[:, 1]) + gap + rng.uniform(-noise, noise, xs.size)
    scanner = apply(frame, np.column_stack([pj[:, :2], z]))
    assert np.allclose(scanner[:, :2], np.column_stack([xs.ravel(), ys.ravel()]), atol=1e-12)
    heights = scanner[:, 2].reshape(shape).copy()
    if hole is not None:
        out = np.hypot(pj[:, 0] - hole[0], pj[:, 1] - hole[1]) <= hole[2]
        heights[out.reshape(shape)] = np.nan
    ok = ~np.isnan(heights.ravel())
    return heights, pj[ok, :2]


def plane_tilt(wall, region) -> float:
    """Slope angle [rad] of the least-squares plane of ``wall`` over ``region``: how far the
    levelled frame of a scan of it leans from the joint frame."""
    x, y = np.meshgrid(np.linspace(region[0], region[1], 60), np.linspace(region[2], region[3], 60))
    z = wall(x.ravel(), y.ravel())
    a = np.column_stack([x.ravel(), y.ravel(), np.ones(x.size)])
    gx, gy, _ = np.linalg.lstsq(a, z, rcond=None)[0]
    return float(np.arctan(np.hypot(gx, gy)))
