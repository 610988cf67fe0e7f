#!/usr/bin/env bash
# Test layout: every test under tests/ sits at the path of the source it tests
# (tests/drivers/mavlink/gcs_status_test.cpp tests drivers/mavlink/gcs_status.{hpp,cpp}) or is
# listed under the architecture's "Topic tests" heading; every test listed there exists.
# Usage: tests/lint/test_layout.sh SOURCE_DIR
set -euo pipefail
src=${1:?usage: test_layout.sh SOURCE_DIR}
cd "$src"
arch=ARCHITECTURE.md
[ -f docs/architecture.md ] && arch=docs/architecture.md
# The backquoted tests/ paths of the Topic tests section (a path ending in / covers its folder).
topics=$(awk '/^## Topic tests/ { on = 1; next } /^## / { on = 0 } on' "$arch" |
  grep -o '`tests/[^`]*`' | tr -d '`' | sort -u || true)
if [ -z "$topics" ]; then
  echo "test_layout: $arch has no \"## Topic tests\" section listing tests/ paths"
  exit 1
fi
listed() {
  local t
  for t in $topics; do
    if [ "$t" = "$1" ] || { [ "${t%/}" != "$t" ] && [ "${1#"$t"}" != "$1" ]; }; then return 0; fi
  done
  return 1
}
bad=0
count=0
while IFS= read -r f; do
  count=$((count + 1))
  rel=${f#tests/}
  dir=$(dirname "$rel")
  base=$(basename "$rel")
  stem=${base%_test.*}
  stem=${stem%_benchmark.cpp}
  if [ -e "$dir/$stem.cpp" ] || [ -e "$dir/$stem.hpp" ] || listed "$f"; then continue; fi
  echo "test_layout: $f: no $dir/$stem.cpp or .hpp, and not a topic test in $arch"
  bad=1
done < <(find tests -path tests/node_modules -prune -o -type f \
  \( -name '*_test.cpp' -o -name '*_test.mjs' -o -name '*_test.py' -o -name '*_benchmark.cpp' \) \
  -print | sort)
for t in $topics; do
  if [ ! -e "$t" ]; then
    echo "test_layout: $arch lists $t as a topic test, but there is no such file"
    bad=1
  fi
done
[ "$bad" -eq 0 ] && echo "test_layout: $count tests, each at its source's path or a topic test in $arch"
exit "$bad"
