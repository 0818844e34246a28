# SPDX-License-Identifier: MIT
"""CLI commands: one module each, exposing add_parser(subparsers)."""
