# SPDX-License-Identifier: MIT
"""A YAML document as plain data plus the line of every key, from yaml's composed node tree.

yaml.safe_load forgets where a value came from; yaml.compose keeps a mark on every node, so a
scene's error can name the key path and its line (1-based) in the file.
"""
from __future__ import annotations

import yaml


class SceneError(ValueError):
    """A scene that cannot be run: the message names the file, the key path and its line."""


def _scalar(node: yaml.ScalarNode):
    # The safe constructor gives the value yaml 1.1 would (int, float, bool, null, str).
    return yaml.SafeLoader.construct_scalar(_LOADER, node) if node.tag.endswith(":str") else \
        _LOADER.construct_object(node, deep=True)


_LOADER = yaml.SafeLoader("")


def compose(text: str, source: str):
    """(data, lines): the document as dicts/lists/scalars and {key path tuple: line}."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = f", line {mark.line + 1}" if mark else ""
        raise SceneError(f"{source}{where}: not valid YAML: {getattr(err, 'problem', err)}") from err
    lines: dict = {}
    if root is None:
        raise SceneError(f"{source}: the file is empty")
    return _convert(root, (), lines, source), lines


def _convert(node, path: tuple, lines: dict, source: str):
    lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        out = {}
        for key_node, value_node in node.value:
            key = _scalar(key_node) if isinstance(key_node, yaml.ScalarNode) else None
            if not isinstance(key, str):
                raise SceneError(f"{source}, line {key_node.start_mark.line + 1}: keys must be "
                                 f"words, got {key!r}")
            if key in out:
                raise SceneError(f"{source}, line {key_node.start_mark.line + 1}: key "
                                 f"{'.'.join(map(str, path + (key,)))!r} is given twice")
            lines[path + (key,)] = key_node.start_mark.line + 1
            out[key] = _convert(value_node, path + (key,), lines, source)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_convert(item, path + (i,), lines, source) for i, item in enumerate(node.value)]
    return _scalar(node)
