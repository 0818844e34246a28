# SPDX-License-Identifier: MIT
"""Numbers that docs repeat from a bench report are the report's (issue 30, item 9): the tables of
docs/tunnel.md "Verification of the intact tunnel against Kirsch" are bench/results/kirsch.md's
rows (written by bench/bench_kirsch.py), cell for cell, so a re-run bench that changes them fails
here until the page is updated. No FE stack needed: the files are read as text."""
import os
import re

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


# ---- every number of the README's figure tables is in the report its row cites (issue 39, item 7)

_NUMBER = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?(?:e[-+]?\d+)?)(?![\w])")
_REPORT = re.compile(r"`(?:bench/results/)?([\w.]+\.md)`")
#: numbers of a README figure row that are not a report's measurement: {(row start, number): why}
NOT_FROM_THE_REPORT = {
    ("elastic-plastic contact", "1e-10"): "a test tolerance (tests/python/test_contact_plastic.py)",
    ("equivalent continuum", "1e-9"): "a test tolerance (tests/python/test_fem_continuum.py)",
    ("equivalent continuum", "64.7"): "the discrete tunnel's time in continuum.md before issue 31 (git history)",
    ("equivalent continuum", "3.8"): "the mesh check's mixed sidewall 16.363 mm against the discrete 17.002 mm",
    ("equivalent continuum", "3.0"): "the mesh check's mixed sidewall 16.490 mm against the discrete 17.002 mm",
    ("FE, jointed analysis against", "60"): "the joints' dips, 60°/30° (the case, not a result)",
    ("FE, jointed analysis against", "30"): "the joints' dips, 60°/30° (the case, not a result)",
    ("FE, jointed analysis at 1M", "1.3"): "the issue's target ratio",
    ("FE, jointed analysis at 1M", "1.31"): "derived: fem_1m.md's CG iterations 106/81 (column, 1 rank)",
}


def numbers(text: str) -> list[str]:
    return _NUMBER.findall(text)


def written_as(token: str, values) -> bool:
    """`token` (as written: "2.83", "4.9e-7") is one of `values` rounded to the digits written,
    in the same unit or one a factor 10³ or 10² (µs for ns, %) away."""
    v = float(token)
    mantissa, _, _ = token.partition("e")
    digits = len(mantissa.split(".")[1]) if "." in mantissa else 0
    for scale in (1.0, 1e3, 1e-3, 1e2, 1e-2):
        for x in values:
            if "e" in token:
                if x != 0 and f"{x * scale:.{digits}e}" == f"{v:.{digits}e}":
                    return True
            elif abs(round(x * scale, digits) - v) < 1e-9:
                return True
    return False


def readme_figure_rows():
    """(row text, first cell, [reports]) of the README's table rows that cite bench reports: in
    the row itself, or in the heading of the section the table sits in."""
    reports = set(os.listdir(os.path.join(ROOT, "bench", "results")))
    heading_cites, rows = [], []
    for line in read("README.md").splitlines():
        if line.startswith("#"):
            heading_cites = [r for r in _REPORT.findall(line) if r in reports]
        elif line.startswith("| ") and not line.startswith("| ---"):
            cited = [r for r in _REPORT.findall(line) if r in reports] or heading_cites
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cited and cells[0] not in ("what", "setting"):
                rows.append((" | ".join(cells[1:]), cells[0], cited))
    return rows


def test_readme_figures_are_the_numbers_of_the_reports_they_cite():
    rows = readme_figure_rows()
    assert len(rows) >= 20, rows         # the speed-against-error and FE-settings tables
    stale = []
    for text, name, cited in rows:
        values = [float(x) for r in cited for x in numbers(read("bench", "results", r))]
        for token in numbers(text):
            if not written_as(token, values) and not any(
                    name.startswith(start) and token == number for start, number in NOT_FROM_THE_REPORT):
                stale.append(f"{name[:40]!r}: {token} not in {', '.join(cited)}")
    assert not stale, "README figures that their report does not give:\n" + "\n".join(stale)


def test_a_stale_figure_would_be_found():
    # the check itself: the rounding rule and the unit steps it allows, and no more
    assert written_as("2.83", [2.8312]) and written_as("64.7", [64.71]) and written_as("2.2", [2200.0])
    assert written_as("4.9e-7", [4.93e-07]) and written_as("0.0046", [4.63e-03])
    assert not written_as("0.0047", [4.63e-03]) and not written_as("64.71", [7.07, 8.4])


# ---- the planner's discrete-or-smeared evidence is the continuum bench's report (issue 39, item 7)

def _percent(cell: str) -> list[float]:
    return [abs(float(x)) / 100.0 for x in re.findall(r"[-+]?\d+\.?\d*(?= %)", cell)]


def test_smeared_evidence_of_the_planner_is_the_continuum_report():
    """defaults.SMEARED_EVIDENCE = the tunnel rows of bench/results/continuum.md: per s/a the larger
    of the crown and sidewall gaps and the speed-up of the all-smeared and the mixed model; at the
    spacing of the mesh check, the largest gap over its meshes (against the discrete model)."""
    from rockjoint.scenes import defaults
    report = read("bench", "results", "continuum.md")
    tunnel = report.split("## tunnel", 1)[1].split("## blocky", 1)[0]
    expected = {}
    for s, ratio, _crowns, crown, side, _times, speed in table_rows(tunnel, "| s [m] | s/a |"):
        (cs, cm), (ss, sm) = _percent(crown), _percent(side)
        (us, um) = (float(x) for x in re.findall(r"([\d.]+)x", speed))
        expected[float(ratio)] = [max(cs, ss), us, max(cm, sm), um]
    discrete = next(r for r in table_rows(tunnel, "| model | cells |") if r[0] == "discrete")
    crown_d, side_d = float(discrete[3]), float(discrete[4])
    finest = min(expected)
    for _h, smeared, mixed in table_rows(tunnel, "| far-field size h [m] |"):
        for k, cell in ((0, smeared), (2, mixed)):
            crown, side = (float(x) for x in cell.split(",")[1].split("/"))
            gap = max(abs(crown / crown_d - 1), abs(side / side_d - 1))
            expected[finest][k] = max(expected[finest][k], gap)
    given = {row[0]: list(row[1:]) for row in defaults.SMEARED_EVIDENCE}
    assert sorted(given) == sorted(expected)
    for ratio, row in expected.items():
        # the report prints gaps to 0.1 % (the mesh check's to 1 µm) and speed-ups to 0.1x
        for value, measured, resolution in zip(given[ratio], row, (1.5e-3, 0.051, 1.5e-3, 0.051)):
            assert value == pytest.approx(measured, abs=resolution), (ratio, given[ratio], row)


def test_continuum_page_table_is_the_bench_report():
    """docs/equivalent-continuum.md's tunnel table at s = 0.25 m: bench/results/continuum.md's
    model rows (cells, crown / sidewall to 0.01 mm, errors vs discrete, time)."""
    report = read("bench", "results", "continuum.md").split("## tunnel", 1)[1].split("###", 1)[0]
    doc = table_rows(read("docs", "equivalent-continuum.md"), "| model | cells | crown / sidewall [mm] |")
    measured = {r[0]: r for r in table_rows(report, "| model | cells |")}
    assert len(doc) == len(measured)
    for name, cells, displacement, error, seconds in doc:
        kind, _, _ = name.partition(" (")
        m = measured[kind]
        assert cells == m[1], kind
        assert displacement == f"{float(m[3]):.2f} / {float(m[4]):.2f}", kind
        if kind not in ("discrete", "intact"):
            assert error == f"{m[5]} / {m[6]}", kind
        assert seconds.split()[0] == m[7], kind
        if "x" in seconds:
            assert re.search(r"\(([\d.]+)x", seconds).group(1) == m[8].rstrip("x"), kind


# ---- docs pages: a paragraph that cites a bench report gives that section's reports' numbers

_CITED = re.compile(r"bench/results/([\w.]+\.md)")
_HISTORY = "an earlier run, stated with its date or commit on the page (git history), not today's report"
_ON_PAGE = "a run stated on the page with its command, not kept as a report row"
#: numbers of a docs paragraph citing a report that are not the report's: {(page, number): why}
DOCS_NOT_FROM_THE_REPORT = {
    ("equivalent-continuum.md", "9.5"): "derived: 64.7 s (the 2026-11-26 report) / 6.81 s",
    ("equivalent-continuum.md", "2756"): _HISTORY, ("equivalent-continuum.md", "89"): _HISTORY,
    ("fem.md", "1.473"): _ON_PAGE, ("fem.md", "1.521"): _ON_PAGE, ("fem.md", "1.501"): _ON_PAGE,
    ("fem.md", "85"): _ON_PAGE, ("fem.md", "121"): _ON_PAGE,
    ("fem.md", "89"): _ON_PAGE,
    ("fem.md", "106"): "the sum of fem_1m.md's Krylov iterations per Newton step (column, 1 rank)",
    ("fem.md", "119"): "the sum of fem_1m.md's Krylov iterations per Newton step (blocky, 1 rank)",
    ("fem.md", "20e9"): "an input: Young's modulus in a code example",
    ("fem.md", "1.04"): _ON_PAGE,
    ("fem.md", "1.24"): "derived: newton_levers.md's 73 against fem_dolfinx0.11.md's 59 (column)",
    ("fem.md", "1.12"): "derived: newton_levers.md's 74 against fem_dolfinx0.11.md's 66 (blocky)",
    ("flow.md", "1600"): "flow.md's CG iterations for both gradients (3142) halved, rounded",
    ("flow.md", "72"): "a load of the tight joint of tests/python/test_flow_contact_set.py",
    ("scenes.md", "31.6"): "accuracy_ladder.md's resolution rows (the planner's source)",
    ("scenes.md", "16.8"): "accuracy_ladder.md's resolution rows (the planner's source)",
    ("scenes.md", "10.1"): "accuracy_ladder.md's resolution rows (the planner's source)",
    ("tunnel.md", "268"): "the mesh's joint count (meshes.tunnel_section), not a timing",
    ("tunnel.md", "13.2"): _ON_PAGE, ("tunnel.md", "14.4"): _ON_PAGE, ("tunnel.md", "11.9"): _ON_PAGE,
    ("tunnel.md", "9.2"): _ON_PAGE, ("tunnel.md", "8.6"): _ON_PAGE, ("tunnel.md", "7.7"): _ON_PAGE,
    ("tunnel.md", "8.4"): _HISTORY, ("tunnel.md", "0.66"): _ON_PAGE, ("tunnel.md", "4.5"): _ON_PAGE,
    ("tunnel.md", "0.25"): "an input: the demo's mesh size at the wall",
    ("tunnel.md", "54"): "the demo mesh's block count (demo output), not a timing",
    ("tunnel.md", "2207"): "the demo mesh's joint facet pairs (demo output), not a timing",
    ("tunnel.md", "4.8"): _HISTORY,
}


def docs_report_figures():
    """(page, number, its context) of every number in a docs paragraph that cites a bench report,
    checked against the reports its section (## heading) cites."""
    out = []
    for page in sorted(os.listdir(os.path.join(ROOT, "docs"))):
        if not page.endswith(".md"):
            continue
        for section in re.split(r"\n(?=## )", read("docs", page)):
            cited = sorted({c for c in _CITED.findall(section)
                            if os.path.exists(os.path.join(ROOT, "bench", "results", c))})
            if not cited:
                continue
            values = [float(x) for c in cited for x in numbers(read("bench", "results", c))]
            for paragraph in re.split(r"\n\s*\n|\n(?=[*|-] )|\n(?=\d+\. )", section):
                if not _CITED.search(paragraph):
                    continue
                flat = " ".join(paragraph.split())
                for m in _NUMBER.finditer(flat):
                    if not written_as(m.group(1), values):
                        out.append((page, m.group(1), flat[max(0, m.start() - 50):m.end() + 15]))
    return out


def test_docs_figures_are_the_numbers_of_the_reports_they_cite():
    stale = [f"docs/{page}: {n} (…{context}…)" for page, n, context in docs_report_figures()
             if (page, n) not in DOCS_NOT_FROM_THE_REPORT]
    assert not stale, "docs figures that their section's reports do not give:\n" + "\n".join(stale)
    # and every exemption still names a number the page writes (none kept after its figure went)
    written = {(page, n) for page, n, _ in docs_report_figures()}
    assert set(DOCS_NOT_FROM_THE_REPORT) <= written, set(DOCS_NOT_FROM_THE_REPORT) - written
