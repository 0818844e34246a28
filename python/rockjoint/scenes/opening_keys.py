# SPDX-License-Identifier: MIT
"""A tunnel's `geometry.opening` (docs/scenes.md, docs/tunnel.md): its shape and dimensions as
engineers give them, checked key by key, and the check that it lies inside the section.

- ``shape: circle``: ``centre`` and ``radius``.
- ``shape: D``: an arched crown on vertical walls with a flat floor: ``span`` (the width between
  the walls), ``wall_height`` (springline to floor) and ``arch_radius`` (default span / 2: a
  semicircular crown; larger: a flatter segmental crown through the wall tops).
- ``shape: horseshoe``: the same crown and walls over a curved floor, the invert, sagging
  ``invert_depth`` below the wall feet (at most span / 2: a semicircular invert).

For the D and the horseshoe ``centre`` is the middle of the springline (where the crown meets the
walls). The outline is meshes.HorseshoeOpening's (scenes.geometry.opening builds it).
"""
from __future__ import annotations

from . import geometry
from .fields import ListOf, Mapping, Quantity, Text

_POSITIVE = dict(low=0.0, open_low=True)
#: the keys each shape needs, and those it may take
_NEEDS = {"circle": ("radius",), "D": ("span", "wall_height"), "horseshoe": ("span", "wall_height", "invert_depth")}
_TAKES = {"circle": (), "D": ("arch_radius",), "horseshoe": ("arch_radius",)}


def _opening_rule(o, path, c):
    shape = o["shape"]
    for key in _NEEDS[shape]:
        if key not in o:
            c.fail(path, f"missing key {key!r} (needed for shape {shape})")
    for key in ("radius", "span", "wall_height", "arch_radius", "invert_depth"):
        if key in o and key not in _NEEDS[shape] + _TAKES[shape]:
            c.fail(path + (key,), f"not used by shape {shape}")
    if shape == "circle":
        return
    half = 0.5 * o["span"]
    if o.get("arch_radius", half) < half:
        c.fail(path + ("arch_radius",), f"{o['arch_radius']:g} m is less than half the span ({half:g} m): "
                                        "the arch cannot reach both walls")
    if shape == "horseshoe" and not 0.0 < o["invert_depth"] <= half:
        c.fail(path + ("invert_depth",), f"{o['invert_depth']:g} m is out of range: the invert sags more than 0 "
                                         f"(a flat floor is shape D) and at most half the span ({half:g} m: a "
                                         "semicircular invert)")


OPENING = Mapping({"shape": Text(choices=tuple(_NEEDS)), "centre": ListOf(Quantity("length"), length=(2, 3)),
                   "radius": Quantity("length", required=False, **_POSITIVE),
                   "span": Quantity("length", required=False, **_POSITIVE),
                   "wall_height": Quantity("length", required=False, **_POSITIVE),
                   "arch_radius": Quantity("length", required=False, **_POSITIVE),
                   "invert_depth": Quantity("length", required=False, low=0.0)},
                  required=False, rule=_opening_rule)


def check_inside(g, c) -> None:
    """The opening of the checked geometry section `g` lies strictly inside its section."""
    x0, y0, x1, y1 = geometry.opening(g).bounds()
    if not (0.0 < x0 and x1 < g["width"] and 0.0 < y0 and y1 < g["height"]):
        c.fail(("geometry", "opening"), f"the opening is not inside the section: it spans x {x0:g} .. {x1:g} m, "
                                        f"{'z' if 'length' in g else 'y'} {y0:g} .. {y1:g} m, the section "
                                        f"[0, {g['width']:g}] x [0, {g['height']:g}] m (outside or touching "
                                        "its boundary)")
