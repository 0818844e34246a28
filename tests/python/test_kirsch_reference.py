# SPDX-License-Identifier: MIT
"""rockjoint.reference.kirsch against Kirsch's closed forms and against itself.

Independent checks: the wall values quoted by Brady & Brown (σ_θθ = p(3-K) at the sidewall, p(3K-1)
at the crown, u_r = -(pa/4G)[(1+K) - (1-K)(3-4ν)cos 2θ]), the Lamé hole under hydrostatic stress
(σ_θθ = p(1 + a²/r²), u_r = -p a²/(2G r)), a traction-free wall, the far field, and the stress
recomputed from the displacement field by central differences and plane-strain Hooke's law.
"""
import math

import numpy as np
import pytest

from rockjoint.reference import KirschSolution

P, K, A, E, NU = 10e6, 0.6, 3.0, 20e9, 0.3
G = E / (2 * (1 + NU))
K_SOL = KirschSolution(A, P, K, E, NU, (1.0, 2.0))


def test_wall_values_of_brady_and_brown():
    srr, stt, srt = K_SOL.polar_stress(np.full(2, A), np.array([0.0, math.pi / 2]))
    assert stt == pytest.approx([P * (3 - K), P * (3 * K - 1)], rel=1e-14)
    assert np.abs(srr).max() < 1e-9 * P and np.abs(srt).max() < 1e-9 * P  # traction-free wall
    th = np.linspace(0, 2 * math.pi, 13)
    ur, ut = K_SOL.excavation_displacement(np.full(th.size, A), th)
    assert ur == pytest.approx(-(P * A / (4 * G)) * ((1 + K) - (1 - K) * (3 - 4 * NU) * np.cos(2 * th)), rel=1e-13)
    assert ut == pytest.approx(-(P * A / (4 * G)) * (1 - K) * (3 - 4 * NU) * np.sin(2 * th), abs=1e-13 * P * A / G)
    assert K_SOL.wall_hoop_stress(th) == pytest.approx(K_SOL.polar_stress(np.full(th.size, A), th)[1], rel=1e-13)


def test_hydrostatic_field_is_lames_hole():
    lame = KirschSolution(A, P, 1.0, E, NU)
    r = np.linspace(A, 10 * A, 7)
    srr, stt, srt = lame.polar_stress(r, np.full(r.size, 0.3))
    assert srr == pytest.approx(P * (1 - A ** 2 / r ** 2), abs=1e-9 * P)
    assert stt == pytest.approx(P * (1 + A ** 2 / r ** 2), rel=1e-14)
    assert np.abs(srt).max() == 0.0
    ur, ut = lame.excavation_displacement(r, np.full(r.size, 0.3))
    assert ur == pytest.approx(-P * A ** 2 / (2 * G * r), rel=1e-14) and np.abs(ut).max() == 0.0


def test_far_field_is_the_in_situ_stress():
    s = K_SOL.cartesian_stress(np.array([1.0 + 1e5]), np.array([2.0 + 3e4]))[0]
    assert s == pytest.approx(np.array([[-K * P, 0.0], [0.0, -P]]), abs=1e-6 * P)


def test_stress_is_hookes_law_of_the_displacement():
    """Total displacement = excavation part + the far field's uniform strain (tension positive)."""
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    sx, sy = -K * P, -P
    exx, eyy = ((1 - NU) * sx - NU * sy) / (2 * G), ((1 - NU) * sy - NU * sx) / (2 * G)

    def u(x, y):
        return K_SOL.excavation_displacement_xy(x, y) + np.array([exx * (x - 1.0), eyy * (y - 2.0)])

    h = 1e-5
    for x, y in ((5.0, 3.0), (1.0, 5.5), (-3.0, -1.0), (4.0, 2.0), (-1.2, 4.4)):
        grad = np.stack([(u(x + h, y) - u(x - h, y)) / (2 * h), (u(x, y + h) - u(x, y - h)) / (2 * h)], axis=1)
        eps = 0.5 * (grad + grad.T)
        sigma = 2 * G * eps + lam * np.trace(eps) * np.eye(2)
        assert sigma == pytest.approx(K_SOL.cartesian_stress(x, y), abs=1e-6 * P)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="radius must be a finite number > 0"):
        KirschSolution(-1.0, P, K)
    with pytest.raises(ValueError, match="poisson must be in"):
        KirschSolution(A, P, K, E, 0.5)
    with pytest.raises(ValueError, match="r must be >= the radius"):
        K_SOL.polar_stress(np.array([1.0]), np.array([0.0]))
