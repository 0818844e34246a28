# SPDX-License-Identifier: MIT
"""Sphinx configuration of rockjoint's reference (built by scripts/docs.sh, issue 42 item 3)."""
import os

project = "rockjoint"
author = "the rockjoint developers"
copyright = "the rockjoint developers (MIT licence)"
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "sphinx.ext.doctest",
              "sphinx.ext.mathjax", "breathe"]
source_suffix = {".md": "markdown"}
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
root_doc = "index"
exclude_patterns = ["_build", "_doxygen"]
html_theme = "furo"
autodoc_member_order = "bysource"
autodoc_typehints = "description"
# The C++ headers, read by doxygen (scripts/docs.sh writes its XML into _doxygen/xml).
breathe_projects = {"rockjoint": os.path.join(os.path.dirname(__file__), "_doxygen", "xml")}
breathe_default_project = "rockjoint"
# Nitpicky: every cross-reference resolves, except to the libraries rockjoint builds on, whose
# inventories are not at hand offline (no intersphinx): numpy, scipy, dolfinx, petsc4py, ufl, ...
nitpicky = True
nitpick_ignore_regex = [(r"py:.*", r"(numpy|np|scipy|dolfinx|petsc4py|ufl|basix|mpi4py|matplotlib|"
                                   r"collections|typing|pathlib|argparse|logging)(\..*)?")]
