#!/usr/bin/env bash
# Regenerates docs/configuration.md from `rovctl params`, or with --check fails when it is stale.
# Usage: bash deploy/docs.sh [--check] [ROVCTL_BINARY]   (default binary: ./build/rovctl)
set -euo pipefail
cd "$(dirname "$0")/.."

check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
fi
rovctl=${1:-./build/rovctl}
page=docs/configuration.md
if [ ! -x "$rovctl" ]; then
  echo "deploy/docs.sh: $rovctl is not an executable rovctl (build it first: bash deploy/setup.sh)" >&2
  exit 2
fi

generated=$(mktemp)
trap 'rm -f "$generated" "$generated.page"' EXIT
"$rovctl" params >"$generated"

{
  cat <<'HEAD'
# Configuration reference

Every parameter rovctl reads from its YAML config: its key, unit, range, default and meaning. A
config names only what it changes; anything else takes the default below. Every command validates
the whole config at start-up and stops with exit 2, naming the file, line and key, on a value out
of range, a key it does not know, or a wrong type. `rovctl params --config F` prints the same
table with F's values in place of the defaults.

This page is the output of `rovctl params`, written by `bash deploy/docs.sh`; a test
(`ctest --test-dir build -R Docs.ConfigurationReference`) fails when the two differ.

HEAD
  cat "$generated"
} >"$generated.page"

if [ "$check" -eq 1 ]; then
  if ! diff -u "$page" "$generated.page"; then
    echo "deploy/docs.sh: $page differs from \`rovctl params\` (above); run: bash deploy/docs.sh" >&2
    exit 1
  fi
  echo "deploy/docs.sh: $page matches \`rovctl params\`"
else
  mkdir -p docs
  mv "$generated.page" "$page"
  echo "deploy/docs.sh: wrote $page"
fi
