# SPDX-License-Identifier: MIT
"""Sphinx configuration of rockjoint's reference (built by scripts/docs.sh, issue 42 item 3)."""
import os

project = "rockjoint"
author = "the rockjoint developers"
copyright = "the rockjoint developers (MIT licence)"
# No napoleon: the docstrings are plain reST (no Google/NumPy sections), and napoleon read a
# property docstring such as "Eq. (1): a = ..." as "type: description". The docstrings' >>>
# examples run under pytest --doctest-modules (ctest doctest), not Sphinx's doctest builder.
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax", "breathe"]
source_suffix = {".md": "markdown"}
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
root_doc = "index"
exclude_patterns = ["_build", "_doxygen", "build.sh", "Doxyfile"]
html_theme = "furo"
autodoc_member_order = "bysource"
autodoc_typehints = "description"
# The C++ headers, read by doxygen (docs/build.sh writes its XML into $ROCKJOINT_DOXYGEN_DIR/xml).
breathe_projects = {"rockjoint": os.path.join(
    os.environ.get("ROCKJOINT_DOXYGEN_DIR", os.path.join(os.path.dirname(__file__), "_build", "doxygen")),
    "xml")}
breathe_default_project = "rockjoint"
# Nitpicky: every cross-reference resolves, except to the libraries rockjoint builds on, whose
# inventories are not at hand offline (no intersphinx, no network in CI): numpy, scipy, dolfinx
# (also as `fem.Function`, the `from dolfinx import fem` spelling of the type hints), petsc4py,
# ufl, basix, mpi4py, matplotlib, and Python's own standard library (collections, typing, os,
# pathlib, argparse, logging). The Debian root holds petsc4py's objects.inv only where its -doc
# package happens to be installed, so it is not relied upon.
nitpicky = True
# The C++ reference names two external libraries with no Sphinx inventory either: Eigen (the
# topography height grids, Eigen::Array) and GSL (gsl_function, the quadrature's integrand).
nitpick_ignore_regex = [(r"cpp:identifier", r"(Eigen|gsl_function)\b.*"),
                        (r"py:.*", r"(numpy|np|scipy|dolfinx|fem|petsc4py|ufl|basix|mpi4py|matplotlib|"
                                   r"collections|typing|os|pathlib|argparse|logging|PETSc)(\..*)?")]


def _register_breathe_labels(app, doctree):
    """Make breathe's doxygen targets (one per class, member, enumerator) resolvable labels.

    Breathe 5.1 puts an empty target, named after the doxygen id, in front of each declaration and
    links the references of the doxygen text to it as a std label. Sphinx's standard domain misses
    most of them: docutils' PropagateTargets moves a target's id onto the declaration's first node,
    which the domain skips as part of an object description (desc_*), and the targets of a class's
    members are noted in the nested document breathe parses the class in, not in the page's. Every
    reference between the C++ entries would be an "undefined label". This registers each of those
    targets as an anonymous label of its page, as the standard domain does for any other target.
    """
    from docutils import nodes
    std = app.env.domains.standard_domain
    for target in doctree.findall(nodes.target):
        if target.get("refuri") or not target["names"]:
            continue
        anchor = target.get("refid") or (target["ids"] or [None])[0]
        name = target["names"][0]
        if anchor and name not in std.anonlabels:
            std.anonlabels[name] = app.env.docname, anchor


def _header_names_as_text(app, env, node, contnode):
    """A header file named by doxygen (a class's `#include` line) stays plain text.

    The C++ reference is organised by namespace, not by file, so a header has no entry to link
    to; any other unresolved reference is still a warning (and an error under -W).
    """
    if node.get("refdomain") == "std" and node.get("reftype") == "ref" \
            and node.get("reftarget", "").endswith("_8hpp"):
        return contnode
    return None


def _compiled_public_name(app, env, node, contnode):
    """A type hint naming a compiled class by its home in the extension modules
    (rockjoint._rockjoint.topography.Surface) links to the public name that documents it
    (rockjoint.topography.Surface, or rockjoint.X for the closure laws the package exports)."""
    target = node.get("reftarget", "")
    if node.get("refdomain") != "py" or not target.startswith("rockjoint._rockjoint"):
        return None
    parts = target.split(".")
    name = parts[-1]
    sub = parts[2] if len(parts) > 3 else None
    package = {"_rockjoint_fem_coupling": "fem"}.get(parts[1])
    candidates = [f"rockjoint.{sub}.{name}" if sub else None,
                  f"rockjoint.{package}.{name}" if package else None, f"rockjoint.{name}"]
    py = env.domains["py"]
    for candidate in filter(None, candidates):
        if candidate in py.objects:
            node["reftarget"] = candidate
            return py.resolve_xref(env, node["refdoc"], app.builder, node["reftype"], candidate,
                                   node, contnode)
    return None


def _skip_foreign_imports(app, what, name, obj, skip, options):
    """With :imported-members: a module documents what it re-exports from rockjoint (the compiled
    classes, the FE API of rockjoint.fem), not what it imports from elsewhere (pkgutil,
    importlib, typing)."""
    module = getattr(obj, "__module__", None)
    if what == "module" and isinstance(module, str) and not module.startswith("rockjoint"):
        return True
    return None


def setup(app):
    """Hook the label registration in after the domains have read each document."""
    app.connect("doctree-read", _register_breathe_labels)
    app.connect("missing-reference", _header_names_as_text)
    app.connect("missing-reference", _compiled_public_name)
    app.connect("autodoc-skip-member", _skip_foreign_imports)
