# SPDX-License-Identifier: MIT
"""Kirsch (1898): a circular hole of radius a in an infinite elastic plate under a biaxial far field.

Notation of Brady & Brown (2004), Rock Mechanics for Underground Mining, §7.3: far-field vertical
stress p and horizontal stress K p (compression positive, as rock mechanics writes them); polar
coordinates (r, θ) about the hole's centre, θ anticlockwise from the horizontal x axis (θ = 0: the
sidewall, θ = 90°: the crown). Eqs. (7.7) of Brady & Brown:

    σ_rr = p/2 [(1+K)(1 - a²/r²) - (1-K)(1 - 4a²/r² + 3a⁴/r⁴) cos 2θ]
    σ_θθ = p/2 [(1+K)(1 + a²/r²) + (1-K)(1 + 3a⁴/r⁴) cos 2θ]
    σ_rθ = p/2 [(1-K)(1 + 2a²/r² - 3a⁴/r⁴) sin 2θ]

(compression positive). At the wall σ_θθ = p[(1+K) + 2(1-K) cos 2θ]: p(3-K) at the sidewall,
p(3K-1) at the crown. The excavation-induced displacement (the hole cut in the pre-stressed plate,
relative to the in-situ state; plane strain, shear modulus G, κ = 3 - 4ν; u_r positive outward,
u_θ anticlockwise), Brady & Brown Eqs. (7.8) generalised off the wall:

    u_r = -p/(4G) [(1+K) a²/r - (1-K)((κ+1) a²/r - a⁴/r³) cos 2θ]
    u_θ = -p/(4G) (1-K) [(κ-1) a²/r + a⁴/r³] sin 2θ

At the wall u_r = -(p a/4G)[(1+K) - (1-K)(3-4ν) cos 2θ] (Brady & Brown Eq. 7.8) and
u_θ = -(p a/4G)(1-K)(3-4ν) sin 2θ. The total displacement of the plate loaded with the hole in it
adds the uniform far-field strain; the excavation part is what a staged analysis (in-situ stress,
then excavation) reports.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def _positive(name, value):
    value = float(value)
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"KirschSolution: {name} must be a finite number > 0, got {value!r}")
    return value


@dataclass(frozen=True)
class KirschSolution:
    """Kirsch's hole in a biaxially stressed plate (plane strain for the displacements).

    radius: hole radius a [m]; vertical_stress: p [Pa], compression positive; k0: K = σ_h/σ_v [-];
    young: E [Pa], poisson: ν [-] (for the displacements); centre: (x, y) of the hole [m].
    """

    radius: float
    vertical_stress: float
    k0: float
    young: float = 1.0
    poisson: float = 0.25
    centre: tuple = (0.0, 0.0)

    def __post_init__(self):
        _positive("radius", self.radius)
        for name in ("vertical_stress", "k0"):
            v = float(getattr(self, name))
            if not math.isfinite(v):
                raise ValueError(f"KirschSolution: {name} must be finite, got {v!r}")
        _positive("young", self.young)
        if not (-1.0 < float(self.poisson) < 0.5):
            raise ValueError(f"KirschSolution: poisson must be in (-1, 0.5), got {self.poisson!r}")

    @property
    def shear_modulus(self) -> float:
        """Shear modulus G = E / (2 (1 + ν)) [Pa]."""
        return self.young / (2.0 * (1.0 + self.poisson))

    def polar(self, x, y):
        """(r, θ) [m, rad] of points (x, y) about the centre."""
        dx, dy = np.asarray(x, float) - self.centre[0], np.asarray(y, float) - self.centre[1]
        return np.hypot(dx, dy), np.arctan2(dy, dx)

    def polar_stress(self, r, theta):
        """(σ_rr, σ_θθ, σ_rθ) [Pa], compression positive, Brady & Brown Eq. (7.7)."""
        r, theta = np.asarray(r, float), np.asarray(theta, float)
        if np.any(r < self.radius * (1.0 - 1e-9)):
            raise ValueError(f"KirschSolution: r must be >= the radius {self.radius} (inside the hole there is "
                             f"no rock), got min r = {r.min()!r}")
        p, K, a2 = self.vertical_stress, self.k0, (self.radius / r) ** 2
        c2, s2 = np.cos(2 * theta), np.sin(2 * theta)
        srr = 0.5 * p * ((1 + K) * (1 - a2) - (1 - K) * (1 - 4 * a2 + 3 * a2 * a2) * c2)
        stt = 0.5 * p * ((1 + K) * (1 + a2) + (1 - K) * (1 + 3 * a2 * a2) * c2)
        srt = 0.5 * p * ((1 - K) * (1 + 2 * a2 - 3 * a2 * a2) * s2)
        return srr, stt, srt

    def cartesian_stress(self, x, y):
        """(..., 2, 2) Cartesian stress tensor [Pa], *tension positive* (the continuum convention of
        the FE model), at points (x, y)."""
        r, th = self.polar(x, y)
        srr, stt, srt = (-s for s in self.polar_stress(r, th))
        c, s = np.cos(th), np.sin(th)
        sxx = srr * c * c + stt * s * s - 2 * srt * s * c
        syy = srr * s * s + stt * c * c + 2 * srt * s * c
        sxy = (srr - stt) * s * c + srt * (c * c - s * s)
        return np.stack([np.stack([sxx, sxy], -1), np.stack([sxy, syy], -1)], -2)

    def excavation_displacement(self, r, theta):
        """(u_r, u_θ) [m] caused by cutting the hole in the pre-stressed plate (plane strain):
        u_r positive outward (negative = convergence), u_θ anticlockwise."""
        r, theta = np.asarray(r, float), np.asarray(theta, float)
        p, K, a, G = self.vertical_stress, self.k0, self.radius, self.shear_modulus
        kappa = 3.0 - 4.0 * self.poisson
        ur = -p / (4 * G) * ((1 + K) * a * a / r - (1 - K) * ((kappa + 1) * a * a / r - a ** 4 / r ** 3)
                             * np.cos(2 * theta))
        ut = -p / (4 * G) * (1 - K) * ((kappa - 1) * a * a / r + a ** 4 / r ** 3) * np.sin(2 * theta)
        return ur, ut

    def excavation_displacement_xy(self, x, y):
        """(..., 2) excavation displacement vector [m] at points (x, y)."""
        r, th = self.polar(x, y)
        ur, ut = self.excavation_displacement(r, th)
        c, s = np.cos(th), np.sin(th)
        return np.stack([ur * c - ut * s, ur * s + ut * c], -1)

    def wall_hoop_stress(self, theta):
        """σ_θθ at the wall [Pa], compression positive: p[(1+K) + 2(1-K) cos 2θ]."""
        return self.vertical_stress * ((1 + self.k0) + 2 * (1 - self.k0) * np.cos(2 * np.asarray(theta, float)))
