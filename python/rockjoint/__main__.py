# SPDX-License-Identifier: MIT
"""Command line: `python3 -m rockjoint <command> ...`.

Each command is a module in rockjoint/commands/ with `add_parser(subparsers)` (which sets
`func` on its parser) so commands are added without touching this file.
"""
import argparse
import importlib
import pkgutil
import sys

from . import __version__, commands
from .console import warnings_as_lines
from .law_registry import load_plugins


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m rockjoint",
                                     description="Rough-rock-joint closure laws (rockjoint)")
    parser.add_argument("--version", action="version", version=f"rockjoint {__version__}")
    try:  # laws registered from outside the package (ROCKJOINT_LAWS, entry points)
        load_plugins()
    except ValueError as err:
        print(f"rockjoint: error: {err}", file=sys.stderr)
        return 2
    sub = parser.add_subparsers(dest="command", metavar="command")
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda i: i.name):
        importlib.import_module(f"{commands.__name__}.{info.name}").add_parser(sub)
    args = parser.parse_args(argv)
    warnings_as_lines()
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except (ValueError, OSError) as err:
        print(f"rockjoint {args.command}: error: {err}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
