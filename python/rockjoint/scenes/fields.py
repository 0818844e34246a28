# SPDX-License-Identifier: MIT
"""The small schema language of scene files: each field checks its value and returns it in SI.

A field raises SceneError through `Checker.fail`, which names the key path and its line; a
mapping rejects unknown keys (with the valid ones listed) and missing required ones.
"""
from __future__ import annotations

import abc
import dataclasses
from typing import Any, Callable, Optional

from .units import in_unit_of, parse_quantity
from .yamlnodes import SceneError

MISSING = object()


@dataclasses.dataclass
class Checker:
    """Where values come from: the file name and {key path: line}."""

    source: str
    lines: dict

    def line(self, path: tuple) -> int:
        """The line of `path` in the scene file, or of its nearest ancestor that has one (1 if none)."""
        while path not in self.lines and path:
            path = path[:-1]
        return self.lines.get(path, 1)

    def fail(self, path: tuple, message: str):
        """Raise SceneError naming the file, the line and the key path of `path`, with `message`."""
        key = ".".join(str(p) if not isinstance(p, int) else f"[{p}]" for p in path).replace(".[", "[")
        raise SceneError(f"{self.source}, line {self.line(path)}: {key or 'scene'}: {message}")


class Field(abc.ABC):
    """One entry of the scene schema: `check` turns a value into SI or fails.

    Class attributes: `required` (a missing key fails), `default` (used when it is not required
    and absent) and `doc` (words for the scene reference).
    """

    required = True
    default: Any = MISSING
    doc = ""

    @abc.abstractmethod
    def check(self, value, path: tuple, c: Checker):
        """The value in SI (or the checked structure); c.fail(path, ...) on a bad one."""


@dataclasses.dataclass
class Quantity(Field):
    """A number with a unit of `dimension`, in [low, high] (SI) when given."""

    dimension: str
    low: Optional[float] = None
    high: Optional[float] = None
    required: bool = True
    default: Any = MISSING
    open_low: bool = False

    def check(self, value, path, c):
        """The value in SI units; fails on a bad unit or a value out of [low, high]."""
        try:
            x = parse_quantity(value, self.dimension)
        except ValueError as err:
            c.fail(path, str(err))
        if self.low is not None and (x < self.low or (self.open_low and x == self.low)):
            c.fail(path, f"{value!r} is out of range: must be {'>' if self.open_low else '>='} "
                         f"{in_unit_of(value, self.low, self.dimension)}")
        if self.high is not None and x > self.high:
            c.fail(path, f"{value!r} is out of range: must be <= "
                         f"{in_unit_of(value, self.high, self.dimension)}")
        return x


@dataclasses.dataclass
class Integer(Field):
    """A whole number in [low, high] (high None: no upper bound)."""

    low: int = 0
    high: Optional[int] = None
    required: bool = True
    default: Any = MISSING

    def check(self, value, path, c):
        """The integer; fails on a non-integer (booleans included) or one out of range."""
        if isinstance(value, bool) or not isinstance(value, int):
            c.fail(path, f"expected a whole number, got {value!r}")
        if value < self.low or (self.high is not None and value > self.high):
            c.fail(path, f"{value} is out of range [{self.low}, {self.high if self.high is not None else '∞'}]")
        return value


@dataclasses.dataclass
class Text(Field):
    """A non-empty word, one of `choices` when they are given."""

    choices: Optional[tuple] = None
    required: bool = True
    default: Any = MISSING

    def check(self, value, path, c):
        """The word; fails on a non-string, an empty one or one outside `choices`."""
        if not isinstance(value, str) or not value:
            c.fail(path, f"expected a word, got {value!r}")
        if self.choices is not None and value not in self.choices:
            c.fail(path, f"{value!r} is not one of {', '.join(self.choices)}")
        return value


@dataclasses.dataclass
class Flag(Field):
    """true or false (optional by default)."""

    required: bool = False
    default: Any = MISSING

    def check(self, value, path, c):
        """The boolean; fails on anything else."""
        if not isinstance(value, bool):
            c.fail(path, f"expected true or false, got {value!r}")
        return value


@dataclasses.dataclass
class ListOf(Field):
    """A list whose entries are each an `item`, with an allowed set of lengths or a minimum length."""

    item: Field
    length: Optional[tuple] = None     # allowed lengths
    required: bool = True
    default: Any = MISSING
    min_length: int = 0

    def check(self, value, path, c):
        """The list of checked entries; fails on a non-list or a wrong length."""
        if not isinstance(value, list):
            c.fail(path, f"expected a list, got {value!r}")
        if self.length is not None and len(value) not in self.length:
            c.fail(path, f"expected {' or '.join(map(str, self.length))} entries, got {len(value)}")
        if len(value) < self.min_length:
            c.fail(path, f"expected at least {self.min_length} entries, got {len(value)}")
        return [self.item.check(v, path + (i,), c) for i, v in enumerate(value)]


@dataclasses.dataclass
class Mapping(Field):
    """Fixed keys; `rule(value dict, path, checker)` checks relations between them."""

    fields: dict
    required: bool = True
    default: Any = MISSING
    rule: Optional[Callable] = None

    def check(self, value, path, c):
        """The checked mapping, defaults filled in; fails on unknown, missing or empty keys, then applies `rule`."""
        if value is None:
            value = {}
        if not isinstance(value, dict):
            c.fail(path, f"expected a mapping of {', '.join(self.fields)}, got {value!r}")
        for key in value:
            if key not in self.fields:
                c.fail(path + (key,), f"unknown key {key!r}; expected one of {', '.join(self.fields)}")
        out = {}
        for key, field in self.fields.items():
            if key in value and value[key] is not None:
                out[key] = field.check(value[key], path + (key,), c)
            elif key in value:
                c.fail(path + (key,), "a value is missing")
            elif field.required:
                c.fail(path, f"missing key {key!r}")
            elif field.default is not MISSING:
                out[key] = field.default
        if self.rule is not None:
            self.rule(out, path, c)
        return out


@dataclasses.dataclass
class NamedMapping(Field):
    """Keys are names (joint sets, blocks, boundaries); each value is `item`."""

    item: Field
    required: bool = True
    default: Any = MISSING

    def check(self, value, path, c):
        """{name: checked item}; fails on an empty mapping or a non-mapping."""
        if not isinstance(value, dict) or not value:
            c.fail(path, f"expected a mapping of names, got {value!r}")
        return {k: self.item.check(v, path + (k,), c) for k, v in value.items()}


@dataclasses.dataclass
class Anything(Field):
    """Checked later (law parameters, checked against the law registry)."""

    required: bool = True
    default: Any = MISSING

    def check(self, value, path, c):
        """The value as given (checked later by its owner)."""
        return value
