#!/usr/bin/env bash
# The layering of src/ (docs/ARCHITECTURE.md): no layer includes one above it or a peer
# (tests/tools/check_layers.py). Checks the sources as they are, then that the check fails on
# deliberately wrong includes in a copy (an upward include, a peer include, a folder that is not
# a layer), and that docs/ARCHITECTURE.md lists the layers in the order the check enforces.
# Usage: bash test_layering.sh <granflow binary> <source dir>
set -euo pipefail
src="$2"
py=/usr/bin/python3
check="$src/tests/tools/check_layers.py"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$py" "$check" "$src/src" || fail "the sources break the layering"

expect_violation() {  # what, file to touch (relative to src/), line to add, expected message
  rm -rf "$tmp/src" && cp -r "$src/src" "$tmp/src"
  mkdir -p "$(dirname "$tmp/src/$2")"
  echo "$3" >> "$tmp/src/$2"
  local rc=0
  "$py" "$check" "$tmp/src" > "$tmp/out" 2>&1 || rc=$?
  ((rc == 1)) || { cat "$tmp/out"; fail "$1: the check exited with $rc, expected 1"; }
  grep -qF "$4" "$tmp/out" || { cat "$tmp/out"; fail "$1: no line '$4'"; }
  echo "ok: $1 is refused: $(grep -F "$4" "$tmp/out")"
}
expect_violation "an upward include" grid/Grid.cpp '#include "sim/Simulation.hpp"' \
  "grid/ includes sim/, a layer above it"
expect_violation "a peer include" rheology/Rheology.cpp '#include "levelset/Heaviside.hpp"' \
  "rheology/ includes its peer levelset/"
expect_violation "a folder that is not a layer" newlayer/X.hpp '#include "core/Error.hpp"' \
  "newlayer/: a folder that is not a layer"

# The layer table of docs/ARCHITECTURE.md: its `layer` cells, lowest first, as the check has them.
"$py" "$check" --print-layers > "$tmp/check_layers"
"$py" - "$src/docs/ARCHITECTURE.md" > "$tmp/doc_layers" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
section = text.split("## Layers", 1)[1].split("\n## ", 1)[0]
for line in section.splitlines():
    m = re.match(r"\|\s*\d+\s*\|\s*([^|]+)\|", line)
    if m:
        print(" ".join(re.findall(r"`([a-z]+)/`", m.group(1))))
PY
diff "$tmp/check_layers" "$tmp/doc_layers" || fail "docs/ARCHITECTURE.md's layer table differs from the check's order"
echo "ok: docs/ARCHITECTURE.md lists the $(wc -l < "$tmp/check_layers") ranks of the check"
