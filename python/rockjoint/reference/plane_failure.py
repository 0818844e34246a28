# SPDX-License-Identifier: MIT
"""Limit equilibrium of plane failure (Hoek & Bray 1981, Rock Slope Engineering, §6; Wyllie & Mah
2004, §6.4): a rigid block sliding on one plane that daylights at the toe of the face, cut off at
the back by a vertical tension crack in the ground behind the crest, water standing z_w deep in the
crack and draining along the plane to the toe. Per metre of slope (2D)::

    F = (c A + (W cos ψ_p - U - V sin ψ_p) tan φ) / (W sin ψ_p + V cos ψ_p),
    U = ½ γ_w z_w A   (the plane's water, falling linearly from the crack to the toe),
    V = ½ γ_w z_w²    (the crack's),

A the plane's length and W the block's weight. The block is the polygon toe, crest, the crack's
top and foot, its area by the shoelace formula: the geometry is computed, not taken from the
book's chart forms (which assume the plane passes through the toe, as here).
"""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class PlaneFailure:
    """Slope face `height` H [m] at `face_angle` ψ_f [deg], the plane at `plane_angle` ψ_p [deg]
    through the toe, the crack `crack_distance` b [m] behind the crest; rock unit weight
    `unit_weight` γ [N/m³], water `water_unit_weight` γ_w [N/m³]."""

    height: float
    face_angle: float
    plane_angle: float
    crack_distance: float
    unit_weight: float
    water_unit_weight: float = 9.79e3

    def __post_init__(self):
        if not 0.0 < self.plane_angle < self.face_angle <= 90.0:
            raise ValueError(f"plane failure needs 0 < ψ_p ({self.plane_angle}) < ψ_f ({self.face_angle}) <= 90°")
        if self.crack_depth <= 0.0:
            raise ValueError(f"the crack {self.crack_distance} m behind the crest misses the plane")

    @property
    def _run(self) -> float:
        return self.height / math.tan(math.radians(self.face_angle))

    @property
    def crack_depth(self) -> float:
        """z [m]: the crack from the ground down to the plane."""
        return self.height - (self._run + self.crack_distance) * math.tan(math.radians(self.plane_angle))

    @property
    def plane_length(self) -> float:
        """A [m]: the plane from the toe to the crack's foot."""
        return (self._run + self.crack_distance) / math.cos(math.radians(self.plane_angle))

    @property
    def weight(self) -> float:
        """W [N/m]: γ × the block's area (toe, crest, the crack's top and foot)."""
        xk = self._run + self.crack_distance
        pts = [(0.0, 0.0), (self._run, self.height), (xk, self.height), (xk, self.height - self.crack_depth)]
        area = 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1])))
        return self.unit_weight * area

    def factor_of_safety(self, friction_angle: float, cohesion: float = 0.0, water_depth: float = 0.0) -> float:
        """F for the plane's Coulomb strength (φ [rad], c [Pa]) with water z_w [m] in the crack."""
        if not 0.0 <= water_depth <= self.crack_depth:
            raise ValueError(f"water depth {water_depth} m must be in [0, the crack depth {self.crack_depth:.4g} m]")
        psi = math.radians(self.plane_angle)
        a, w = self.plane_length, self.weight
        u = 0.5 * self.water_unit_weight * water_depth * a
        v = 0.5 * self.water_unit_weight * water_depth ** 2
        resisting = cohesion * a + (w * math.cos(psi) - u - v * math.sin(psi)) * math.tan(friction_angle)
        return resisting / (w * math.sin(psi) + v * math.cos(psi))
