# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint tabulate params.toml -o law.rjt [--plot law.png]`: tabulate a closure
law described in a TOML parameter file (user units MPa, mm, GPa, stated in every key) into a
.rjt table file, and optionally plot the table against its source.

Example parameter file::

    [law]
    model = "barton_bandis"
    initial_normal_stiffness_MPa_per_mm = 20.0
    maximum_closure_mm = 0.3

    [table]
    maximum_stress_MPa = 30.0          # or maximum_closure_mm
    tolerance = 1e-6                   # relative error of σ and k (default: TabulatedLaw.default_tolerance)
    # residual_stiffness_MPa_per_mm = 0.0   (default: 1e-6 σ_max/Δ_max; 0: strict open law)
    # maximum_knots = ...              (default: rockjoint.TabulatedLaw.default_maximum_knots)

Models and their [law] keys are listed by ``--list-models``.
"""
from __future__ import annotations

from ..laws import describe_models, read_law_file
from ..tabulation import plot_table, tabulate


def add_parser(subparsers) -> None:
    """Register the 'tabulate' command and its options."""
    p = subparsers.add_parser(
        "tabulate", help="tabulate a closure law from a TOML parameter file into a .rjt table",
        description="Tabulate a closure law (parameters in a TOML file, units MPa/mm/GPa as "
                    "named in its keys) with error control into a .rjt table file.")
    p.add_argument("parameters", nargs="?", help="TOML parameter file ([law] and [table])")
    p.add_argument("-o", "--output", help="table file to write (.rjt)")
    p.add_argument("--plot", help="PNG of the table against its source")
    p.add_argument("--tolerance", type=float, help="override [table] tolerance")
    p.add_argument("--list-models", action="store_true", help="list models and their keys")
    p.set_defaults(func=run)


def run(args) -> int:
    """Tabulate the law of args.parameters into args.output (or list the models); returns the exit code."""
    if args.list_models:
        print(describe_models())
        return 0
    if not args.parameters or not args.output:
        raise ValueError("give a parameter file and -o/--output (or --list-models)")

    named, options = read_law_file(args.parameters)
    law = named.law
    if law.has_history:
        raise ValueError(f"{args.parameters}: a law with history ({named.key}) is a virgin curve and its "
                         "branches, not one table: tabulate its virgin law (the same [law] keys without "
                         "the history's, model = its virgin)")
    if args.tolerance is not None:
        options["tolerance"] = args.tolerance
    try:
        table = tabulate(law, **options)
    except RuntimeError as err:  # knot budget exceeded: a user-facing error here
        raise ValueError(str(err)) from err
    table.save(args.output)
    print(f"{table.source_model}: {table.knot_count} knots, tolerance {table.tolerance:g} "
          f"(checked σ {table.checked_error_stress:.2g}, k {table.checked_error_stiffness:.2g}), "
          f"closure 0..{table.table_maximum_closure * 1e3:.6g} mm, "
          f"stress 0..{table.table_maximum_stress * 1e-6:.6g} MPa -> {args.output}")
    if args.plot:
        plot_table(table, law, args.plot)
        print(f"plot -> {args.plot}")
    return 0
