#!/usr/bin/env bash
# Function length in the code that flies (app/runtime, control, drivers): prints the 10 longest
# functions and fails when one is longer than MAX_LINES (80). Parameter tables (`describe`) are
# one line per parameter and exempt. Needs Universal Ctags (deploy/setup.sh installs it); without
# it the test reports itself skipped (exit 77).
# Usage: tests/lint/function_length.sh SOURCE_DIR [MAX_LINES]
set -euo pipefail
src=${1:?usage: function_length.sh SOURCE_DIR [MAX_LINES]}
max=${2:-80}
if [[ "$(ctags --version 2>/dev/null || true)" != *"Universal Ctags"* ]]; then
  echo "function_length: Universal Ctags not found (apt-get install universal-ctags): skipped"
  exit 77
fi
cd "$src"
# One line per function definition: length, file:line, name (the exempt parameter tables out).
lengths=$(ctags -x --_xformat='%{end} %n %F %N' --kinds-c++=f --fields=+ne -R --languages=c++ \
    app/runtime control drivers |
  awk '$1 ~ /^[0-9]+$/ && $4 != "describe" { print $1 - $2 + 1, $3 ":" $2, $4 }' | sort -k1,1nr)
if [ -z "$lengths" ]; then
  echo "function_length: ctags listed no functions under app/runtime, control, drivers"
  exit 1
fi
echo "function_length: the 10 longest functions in app/runtime, control, drivers (lines, where, name):"
echo "$lengths" | sed -n '1,10s/^/  /p'
over=$(echo "$lengths" | awk -v max="$max" '$1 > max')
if [ -n "$over" ]; then
  echo "function_length: longer than $max lines (split them into named parts):"
  echo "$over" | sed 's/^/  /'
  exit 1
fi
echo "function_length: none longer than $max lines ($(echo "$lengths" | wc -l) functions)"
