#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Benchmark: Tang & Jiao interaction cell, closed form against the paper's algorithm.

Run:  /usr/bin/python3 bench/bench_interaction_cell.py --build <build dir> [--orders 8 16 32 64]
Runs <build>/bench/bench_interaction_cell (C++, one core), prints a table and writes
bench/results/interaction_cell.md. Times are medians of repeated runs (µs, steady_clock);
errors are relative to the closed form (p̄, P) and max_r |p_num - p| / p(0) on 201 radii.
Cell: theory §7 rock, E* = 26.7 GPa, R = β = 2.5 mm, σ_s = 0.05 mm, a = 0.47 mm (Eq. (1)).
"""
import argparse
import csv
import io
import os
import platform
import subprocess


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(here, "..", "build"))
    ap.add_argument("--orders", type=int, nargs="*", default=[8, 16, 32, 64])
    ap.add_argument("--output", default=os.path.join(here, "results", "interaction_cell.md"))
    args = ap.parse_args()
    exe = os.path.join(args.build, "bench", "bench_interaction_cell")
    if not os.path.exists(exe):
        raise SystemExit(f"{exe} not found: build the target bench_interaction_cell first")
    out = subprocess.run([exe, *map(str, args.orders)], check=True, capture_output=True,
                         text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    header = ("| s = √(A/A0) | n | closed solve [µs] | closed p(r) [µs] | numeric solve [µs] | "
              "numeric p(r) [µs] | iterations (outer, inner) | err p̄ | err P | err p(r) |")
    lines = [header, "|" + "---|" * 10]
    for r in rows:
        lines.append(
            f"| {float(r['area_root']):g} | {r['order']} | {float(r['closed_solve_us']):.3g} | "
            f"{float(r['closed_pressure_us']):.3g} | {float(r['numeric_solve_us']):.3g} | "
            f"{float(r['numeric_pressure_us']):.3g} | "
            f"{r['outer_iterations']}, {r['inner_iterations']} | "
            f"{float(r['err_mean_pressure']):.1e} | {float(r['err_load']):.1e} | "
            f"{float(r['err_pressure']):.1e} |")
    table = "\n".join(lines)
    print(table)
    text = "\n".join([
        "# Interaction cell: closed form vs the paper's algorithm",
        "",
        "Produced by `bench/bench_interaction_cell.py` (C++ executable "
        "`bench_interaction_cell`, one core, medians of repeated runs) on "
        f"{platform.machine()} / {platform.python_version()}.",
        "Closed form: interaction_cell.hpp (theory §5). Numeric: interaction_cell_numeric.hpp "
        "(Sneddon/Abel reduction, n-point Gauss-Legendre rules, bracketed root finds on p̄ "
        "(finite fringe) and δ_loc (self-consistency)).",
        "'solve' = p̄, P, δ_loc of one cell; 'p(r)' = one pressure evaluation.",
        "",
        table,
        "",
    ])
    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"\nwritten: {args.output}")


if __name__ == "__main__":
    main()
