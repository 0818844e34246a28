# SPDX-License-Identifier: MIT
"""The licence (issue 42, item 2): the project's code is MIT (LICENSE at the root), every source
file says so in its first lines (scripts/spdx_headers.py lists and adds the line), and the README
and docs/install.md say what a build that links CHOLMOD's supernodal module and imports gmsh, both
GPL-2+, carries when distributed. Text only: no FE stack needed."""
import importlib.util
import os

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
_spec = importlib.util.spec_from_file_location("spdx_headers", os.path.join(ROOT, "scripts", "spdx_headers.py"))
spdx = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(spdx)


def read(*parts):
    with open(os.path.join(ROOT, *parts), encoding="utf-8") as fh:
        return fh.read()


def test_the_licence_is_mit():
    text = read("LICENSE")
    assert text.startswith("MIT License") and "Permission is hereby granted, free of charge" in text


def test_every_source_file_carries_its_licence_line():
    files = spdx.source_files()
    assert len(files) > 350, len(files)
    kinds = {os.path.splitext(f)[1] for f in files}
    assert {".py", ".cpp", ".hpp", ".sh", ".txt"} <= kinds
    missing = [os.path.relpath(f, ROOT) for f in files if not spdx.has_line(f)]
    assert not missing, "without 'SPDX-License-Identifier: MIT' (python3 scripts/spdx_headers.py --add):\n" \
        + "\n".join(missing)


def test_a_file_without_the_line_is_found_and_fixed(tmp_path):
    script = tmp_path / "x.sh"
    script.write_text("#!/usr/bin/env bash\necho hi\n")
    assert not spdx.has_line(str(script))
    spdx.add(str(script))
    assert script.read_text().splitlines()[:2] == ["#!/usr/bin/env bash", "# SPDX-License-Identifier: MIT"]
    assert spdx.has_line(str(script))


def test_the_gpl_parts_of_a_build_are_named():
    for page in (read("README.md"), read("docs", "install.md")):
        assert "MIT" in page and "CHOLMOD" in page and "GPL-2+" in page and "gmsh" in page
