#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install the built project into a scratch prefix, then configure, build and run a
# downstream project against it with find_package(rockjoint).
set -euo pipefail
build="$1"; src="$2"; work="$build/downstream-check"
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$src" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/downstream"
