"""Numbers that docs repeat from a bench report are the report's (issue 30, item 9): the tables of
docs/tunnel.md "Verification of the intact tunnel against Kirsch" are bench/results/kirsch.md's
rows (written by bench/bench_kirsch.py), cell for cell, so a re-run bench that changes them fails
here until the page is updated. No FE stack needed: the files are read as text."""
import os

import pytest

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def table_rows(text: str, header_start: str) -> list[list[str]]:
    """The cells of the markdown table whose header row starts with `header_start`."""
    lines = text.splitlines()
    starts = [i for i, ln in enumerate(lines) if ln.startswith(header_start)]
    assert len(starts) == 1, f"{header_start!r}: {len(starts)} tables"
    rows = []
    for ln in lines[starts[0] + 2:]:
        if not ln.startswith("|"):
            break
        rows.append([c.strip() for c in ln.strip().strip("|").split("|")])
    assert rows, header_start
    return rows


def read(*parts):
    with open(os.path.join(ROOT, *parts), encoding="utf-8") as fh:
        return fh.read()


def test_tunnel_page_kirsch_tables_are_the_bench_report():
    doc, bench = read("docs", "tunnel.md"), read("bench", "results", "kirsch.md")
    # error against mesh size: the report's columns without its time column
    mesh_doc = table_rows(doc, "| element | a/h | dofs |")
    mesh_bench = [r[:7] for r in table_rows(bench, "| element | a/h | dofs |")]
    assert mesh_doc == mesh_bench
    # domain size: the report's rows without the dofs column, the set-up named once per group
    names = {"excavation": "rollers on the 4 sides, in-situ + excavation",
             "traction": "far-field tractions (top, right), rollers left/bottom"}
    expected, last = [], None
    for loading, wa, _dofs, *errors in table_rows(bench, "| loading | W/a | dofs |"):
        expected.append([names[loading] if loading != last else "", wa, *errors])
        last = loading
    assert table_rows(doc, "| set-up | W/a |") == expected


def test_tunnel_page_states_where_its_kirsch_numbers_come_from():
    doc, bench = read("docs", "tunnel.md"), read("bench", "results", "kirsch.md")
    assert "bash scripts/run.sh python3 bench/bench_kirsch.py" in doc
    stack = bench.split("Produced by `bash scripts/run.sh python3 bench/bench_kirsch.py` (", 1)[1].split(")", 1)[0]
    assert stack.startswith("DOLFINx ") and stack in doc
