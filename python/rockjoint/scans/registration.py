# SPDX-License-Identifier: MIT
"""Registration of two levelled walls for matedness: the in-plane rigid motion (rotation θ
about z, shift t) that carries the upper wall onto the lower one so that the aperture varies
least.

Coarse: for every θ on a grid, masked normalised cross-correlation of the rotated upper
lattice with the lower one over all integer shifts by FFT (Padfield 2012, IEEE TIP 21, 2706:
holes and the walls' outlines are masks, so the outline does not register with itself); a
finer sweep of θ around the best. Fine: Nelder-Mead (scipy.optimize) on (θ, t_x, t_y)
minimising the rms of the aperture's variation, std(z_u(R_θᵀ(q - t)) - z_l(q)) over the
overlap after removing its least-squares plane (the relative tilt, see _difference), with the upper wall interpolated bilinearly (scipy.ndimage.map_coordinates). The
residual misfit is that rms at the optimum: ~0 for perfectly mated walls, otherwise the
unmated roughness plus the interpolation and measurement errors."""
from __future__ import annotations

import dataclasses
import logging
from typing import Tuple

import numpy as np
from scipy import fft, optimize
from scipy.ndimage import map_coordinates

from .errors import NoOverlapError
from .lattice import ScanGrid

log = logging.getLogger(__name__)

COARSE_NODES = 128     # lattice nodes per side of the coarse search, at most


@dataclasses.dataclass(frozen=True)
class Registration:
    """Upper levelled point p lands on lower levelled point q = R(rotation) p + translation."""

    rotation: float             # θ [rad]
    translation: np.ndarray     # t [m], (2,)
    residual_rms: float         # rms of the aperture's variation (less a plane) [m]
    overlap_fraction: float     # shared nodes / valid nodes of the smaller wall
    correlation: float          # coarse normalised cross-correlation at the optimum

    def apply(self, points: np.ndarray) -> np.ndarray:
        """Upper levelled (N, 3) points in the lower levelled frame (z unchanged)."""
        c, s = np.cos(self.rotation), np.sin(self.rotation)
        out = points.copy()
        out[:, 0] = c * points[:, 0] - s * points[:, 1] + self.translation[0]
        out[:, 1] = s * points[:, 0] + c * points[:, 1] + self.translation[1]
        return out


class _Sampler:
    """Bilinear samples of a lattice with holes at arbitrary points: a sample is valid only if
    its four surrounding nodes are (a hole is never bridged)."""

    def __init__(self, grid: ScanGrid):
        self.grid = grid
        self.valid = (~np.isnan(grid.heights)).astype(float)
        self.filled = np.where(self.valid > 0, grid.heights, 0.0)

    def __call__(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        g = self.grid
        idx = np.array([(y - g.origin[1]) / g.spacing_y, (x - g.origin[0]) / g.spacing_x])
        z = map_coordinates(self.filled, idx, order=1, cval=0.0)
        ok = map_coordinates(self.valid, idx, order=1, cval=0.0) > 1 - 1e-9
        return np.where(ok, z, np.nan)


def register(lower: ScanGrid, upper: ScanGrid, *, angle_step: float = np.radians(2.0),
             max_rotation: float = np.pi, min_overlap: float = 0.5,
             min_correlation: float = 0.5, max_misfit: float = 0.5, path=None
             ) -> Registration:
    """Rigid in-plane registration of the (levelled, resampled) upper wall onto the lower one.
    ``max_rotation`` [rad] bounds ``|θ|`` of the search (π: any orientation); ``min_overlap`` is
    the smallest acceptable fraction of the smaller wall that the other covers, and
    ``min_correlation`` the smallest normalised cross-correlation of the walls' heights there
    (mated walls correlate at 0.9 and more, unrelated ones by chance at 0.2-0.4), below which
    NoOverlapError is raised: the walls do not face each other anywhere. The same error if
    the rms of the aperture's variation exceeds ``max_misfit`` times the lower wall's rms
    roughness over the overlap (unrelated walls: about √2 times, chance fits on a small
    overlap: above 0.5; mated walls: the unmated fraction, 0.1-0.3)."""
    h = lower.spacing_x
    need = min_overlap * min(_valid(lower), _valid(upper))
    sampler = _Sampler(upper)
    lx, ly = lower.node_coordinates()
    lz = lower.heights
    # the coarse search needs the long wavelengths only: at most COARSE_NODES per side keeps
    # its ~200 FFT correlations cheap for large scans; Nelder-Mead then works on every node
    k = max(1, int(np.ceil(max(lower.heights.shape + upper.heights.shape) / COARSE_NODES)))
    low_c, up_c = _decimated(lower, k), _decimated(upper, k)
    sampler_c = _Sampler(up_c)
    need_c = min_overlap * min(_valid(low_c), _valid(up_c))

    def coarse(angles):
        best = (-np.inf, 0.0, np.zeros(2))
        for theta in angles:
            score, t = _correlate(low_c, up_c, sampler_c, theta, k * h, need_c)
            if score > best[0]:
                best = (score, theta, t)
        return best

    n = max(1, int(np.ceil(max_rotation / angle_step)))
    score, theta, t = coarse(np.linspace(-n * angle_step, n * angle_step, 2 * n + 1)
                             if max_rotation < np.pi else
                             np.arange(-np.pi, np.pi, angle_step))
    if not np.isfinite(score):
        raise NoOverlapError(path, f"no relative position of the walls shares "
                             f"{min_overlap:.0%} of the smaller wall ({int(need)} nodes)")
    score, theta, t = coarse(theta + np.linspace(-angle_step, angle_step, 17))
    if score < min_correlation:
        raise NoOverlapError(path, f"the walls do not match anywhere: best normalised "
                             f"correlation {score:.2f} < {min_correlation} over "
                             f"{min_overlap:.0%} of the smaller wall (scans of different "
                             "joints, or of no common area?)")

    # θ enters as the arc length θ·radius [m] so that all three unknowns are lengths
    radius = 0.5 * float(np.hypot(*np.ptp(upper.points()[:, :2], axis=0)))
    scale = np.array([1.0 / radius, 1.0, 1.0])

    def misfit(x):
        d, count = _difference(x * scale, lx, ly, lz, sampler)
        return np.std(d) if count >= need else 1e3 * (1 + need - count)

    start = np.array([theta * radius, t[0], t[1]])
    simplex = np.vstack([start, start + np.eye(3) * (k * h / 2)])
    result = optimize.minimize(misfit, start, method="Nelder-Mead",
                               options=dict(initial_simplex=simplex, xatol=1e-4 * h,
                                            fatol=1e-9 * h, maxiter=4000))
    result.x = result.x * scale
    d, count, roughness = _difference(result.x, lx, ly, lz, sampler, lower_too=True)
    if count < need:
        raise NoOverlapError(path, f"registered walls share {count} nodes, fewer than "
                             f"{min_overlap:.0%} of the smaller wall ({int(need)})")
    if np.std(d) > max_misfit * roughness:
        raise NoOverlapError(path, f"the walls do not match: at the best registration the "
                             f"aperture varies by {np.std(d) * 1e3:.3g} mm rms, "
                             f"{np.std(d) / roughness:.2f} of the lower wall's "
                             f"{roughness * 1e3:.3g} mm roughness there (> max_misfit "
                             f"{max_misfit}; scans of different joints, or of no common area?)")
    reg = Registration(float(result.x[0]), np.array(result.x[1:]), float(np.std(d)),
                       count / min(_valid(lower), _valid(upper)), float(score))
    log.info("registration: rotation %.4f°, shift (%.4g, %.4g) mm, overlap %.0f%%, residual "
             "rms of the aperture %.4g mm (correlation %.3f)", np.degrees(reg.rotation),
             *(reg.translation * 1e3), 100 * reg.overlap_fraction, reg.residual_rms * 1e3,
             reg.correlation)
    return reg


def _decimated(grid: ScanGrid, k: int) -> ScanGrid:
    """Every k-th node (the coarse search's lattice)."""
    if k == 1:
        return grid
    return ScanGrid(grid.heights[::k, ::k], grid.spacing_x * k, grid.spacing_y * k,
                    grid.origin, grid.path)


def _valid(grid: ScanGrid) -> int:
    return int(np.count_nonzero(~np.isnan(grid.heights)))


def _detrended(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """z less its least-squares plane in (x, y)."""
    a = np.column_stack([x - x.mean(), y - y.mean(), np.ones(z.size)])
    return z - a @ np.linalg.lstsq(a, z, rcond=None)[0]


def _difference(x, lx, ly, lz, sampler, lower_too: bool = False):
    """Upper minus lower heights at the valid lower nodes for (θ, t_x, t_y), less their
    least-squares plane: two walls levelled on different patches keep a relative tilt that
    is not in the data (frame.py) and must not pull the registration."""
    c, s = np.cos(x[0]), np.sin(x[0])
    qx, qy = lx - x[1], ly - x[2]
    zu = sampler(c * qx + s * qy, -s * qx + c * qy)
    ok = np.isfinite(zu) & np.isfinite(lz)
    d = (zu - lz)[ok]
    if d.size >= 3:
        d = _detrended(lx[ok], ly[ok], d)
    if lower_too:
        return d, d.size, np.std(_detrended(lx[ok], ly[ok], lz[ok]))
    return d, d.size


def _correlate(lower: ScanGrid, upper: ScanGrid, sampler: _Sampler, theta: float, h: float,
               need: float) -> Tuple[float, np.ndarray]:
    """Best masked NCC over integer shifts of the upper wall rotated by θ, and its t."""
    c, s = np.cos(theta), np.sin(theta)
    ux, uy = upper.node_coordinates()
    ok = ~np.isnan(upper.heights)
    rx, ry = c * ux[ok] - s * uy[ok], s * ux[ok] + c * uy[ok]
    origin = np.array([rx.min(), ry.min()])
    shape = (int((ry.max() - origin[1]) / h) + 1, int((rx.max() - origin[0]) / h) + 1)
    gx = origin[0] + h * np.arange(shape[1])
    gy = origin[1] + h * np.arange(shape[0])
    gx, gy = np.meshgrid(gx, gy)
    rotated = sampler(c * gx + s * gy, -s * gx + c * gy)    # U(R_θᵀ q')
    ncc, overlap = _masked_ncc(lower.heights, rotated)
    ncc[overlap < need] = -np.inf
    k = np.unravel_index(int(np.argmax(ncc)), ncc.shape)
    if not np.isfinite(ncc[k]):
        return -np.inf, np.zeros(2)
    di = k[0] if k[0] < ncc.shape[0] // 2 else k[0] - ncc.shape[0]
    dj = k[1] if k[1] < ncc.shape[1] // 2 else k[1] - ncc.shape[1]
    # lower node (i, j) faces rotated node (i - di, j - dj): t = o_L - o' + h (dj, di)
    t = np.asarray(lower.origin) - origin + h * np.array([dj, di])
    return float(ncc[k]), t


def _masked_ncc(a: np.ndarray, b: np.ndarray):
    """Masked normalised cross-correlation c[k] of a[n] with b[n - k] over all shifts k
    (Padfield 2012, Eq. 12), NaN = masked; and the overlap count at each k."""
    shape = (a.shape[0] + b.shape[0], a.shape[1] + b.shape[1])
    ma, mb = ~np.isnan(a), ~np.isnan(b)
    a0 = np.where(ma, a - np.nanmean(a), 0.0)
    b0 = np.where(mb, b - np.nanmean(b), 0.0)
    F = lambda x: fft.rfft2(x, shape)
    corr = lambda fa, fb: fft.irfft2(fa * np.conj(fb), shape)
    fa, fma, fa2 = F(a0), F(ma.astype(float)), F(a0 * a0)
    fb, fmb, fb2 = F(b0), F(mb.astype(float)), F(b0 * b0)
    n = np.maximum(np.rint(corr(fma, fmb)), 1.0)
    sa, sb = corr(fa, fmb), corr(fma, fb)
    num = corr(fa, fb) - sa * sb / n
    var = (corr(fa2, fmb) - sa * sa / n) * (corr(fma, fb2) - sb * sb / n)
    ncc = np.where(var > 0, num / np.sqrt(np.maximum(var, 1e-300)), -np.inf)
    return ncc, n
