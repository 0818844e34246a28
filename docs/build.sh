#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build the API reference site: doxygen over the C++ headers (docs/Doxyfile), then Sphinx over
# docs/*.md and the docstrings (docs/conf.py), every warning an error and every cross-reference
# resolved (-W -n). Runs where DOLFINx and the tools are (the 0.11 userland: scripts/docs.sh
# wraps it; ctest `docs` calls it directly) with rockjoint importable (PYTHONPATH).
#   bash docs/build.sh OUTPUT_DIR    HTML into OUTPUT_DIR/html, doxygen XML into OUTPUT_DIR/doxygen
set -euo pipefail
docs="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="$(mkdir -p "$1" && cd "$1" && pwd)"
export ROCKJOINT_DOXYGEN_DIR="$out/doxygen"
mkdir -p "$ROCKJOINT_DOXYGEN_DIR"
(cd "$docs/.." && doxygen docs/Doxyfile)
python3 -m sphinx -W --keep-going -n -E -b html -q -d "$out/doctrees" "$docs" "$out/html"
echo "docs: $(find "$out/html" -name '*.html' | wc -l) HTML pages in $out/html"
