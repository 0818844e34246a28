# SPDX-License-Identifier: MIT
"""One frame for two walls scanned separately: flip the upper wall (its scanner looked at it
from the other side) and level each wall onto its own mean plane.

A scanner looking down on the upper block's joint face sees it mirrored: the joint frame
(x, y, z) becomes (-x, y, -z) in its frame, a 180° rotation about y (a proper rotation, so
the flipped scan is not a mirror image). Levelling rotates a wall so that its total
least-squares plane (normal = smallest principal axis of the samples, scipy/numpy SVD) is
z = 0 through the centroid; the smallest rotation doing so (Rodrigues) keeps the in-plane
orientation of the scan. The relative tilt of two separately scanned walls is not in the
data, so the common mean plane is z = 0 of both levelled walls; what is left of it after
registration is removed with the common plane of the composite topography."""
from __future__ import annotations

import dataclasses

import numpy as np

from .._rockjoint.topography import PlaneRemoval

FLIP_ABOUT_Y = np.diag([-1.0, 1.0, -1.0])


def plane_removal_mode(plane_removal) -> PlaneRemoval:
    """The PlaneRemoval of a composite topography from its name ("common", "separate" or
    "none") or the enum itself."""
    if isinstance(plane_removal, str):
        try:
            return getattr(PlaneRemoval, plane_removal)
        except AttributeError:
            raise ValueError(f"plane_removal '{plane_removal}' is not one of common, separate, "
                             "none") from None
    return plane_removal


def flip(points: np.ndarray) -> np.ndarray:
    """The upper wall's scan in the joint frame's sense: 180° about y, (x, y, z) -> (-x, y, -z)."""
    return points @ FLIP_ABOUT_Y.T


@dataclasses.dataclass(frozen=True)
class Levelling:
    """levelled = rotation @ (p - centroid) for a scanner-frame point p [m]."""

    rotation: np.ndarray
    centroid: np.ndarray

    def to_scanner(self, levelled: np.ndarray) -> np.ndarray:
        """Levelled (N, 3) points back to the scanner frame."""
        return levelled @ self.rotation + self.centroid

    @property
    def tilt(self) -> float:
        """Angle [rad] between the scanner's z axis and the wall's mean-plane normal."""
        return float(np.arccos(np.clip(self.rotation[2, 2], -1.0, 1.0)))


def level(points: np.ndarray):
    """(levelled points, Levelling): the wall rotated onto its mean plane z = 0."""
    centroid = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centroid, full_matrices=False)
    normal = vt[2] if vt[2, 2] >= 0 else -vt[2]
    rotation = _rotation_onto_z(normal)
    return (points - centroid) @ rotation.T, Levelling(rotation, centroid)


def _rotation_onto_z(n: np.ndarray) -> np.ndarray:
    """Smallest rotation taking the unit vector n (n_z >= 0) onto +z (Rodrigues' formula)."""
    v = np.cross(n, [0.0, 0.0, 1.0])
    s2, c = float(v @ v), float(n[2])
    if s2 < 1e-30:
        return np.eye(3)
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k * ((1 - c) / s2)


def rotation_about_z(angle: float) -> np.ndarray:
    """The 3x3 rotation matrix by angle [rad] about the z axis (counter-clockwise)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
