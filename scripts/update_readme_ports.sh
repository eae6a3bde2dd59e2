#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# README.md's port table of rtl/sc_specular.v is generated from config/interface.json — the source
# every handoff bundle's interface.md is rendered from (`shadecore handoff --print-port-table` prints
# it). This script rewrites the table between the two markers in README.md:
#
#   scripts/update_readme_ports.sh [SHADECORE]            rewrite README.md (atomically)
#   scripts/update_readme_ports.sh --check [SHADECORE]    exit 1 if README.md is out of date (ctest)
#
# SHADECORE defaults to build/cli/shadecore.
set -euo pipefail
cd "$(dirname "$0")/.."
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
exe=${1:-build/cli/shadecore}
begin='<!-- port table: generated from config/interface.json by scripts/update_readme_ports.sh; do not edit -->'
end='<!-- end of port table -->'
grep -qxF "$begin" README.md && grep -qxF "$end" README.md ||
  { echo "update_readme_ports: README.md lacks the port-table markers" >&2; exit 1; }
table=$("$exe" handoff --print-port-table)
if [ $check -eq 1 ]; then tmp=$(mktemp "${TMPDIR:-/tmp}/readme_ports.XXXXXX"); else tmp=$(mktemp README.md.XXXXXX); fi
trap 'rm -f "$tmp"' EXIT
T="$table" awk -v b="$begin" -v e="$end" '
  $0 == b { print; print ENVIRON["T"]; skip = 1; next }
  $0 == e { skip = 0 }
  !skip { print }' README.md > "$tmp"
if [ $check -eq 1 ]; then
  if cmp -s README.md "$tmp"; then echo "update_readme_ports: README.md port table is up to date"; exit 0; fi
  diff README.md "$tmp" || true
  echo "update_readme_ports: FAIL: README.md port table differs from config/interface.json (run scripts/update_readme_ports.sh)"
  exit 1
fi
cmp -s README.md "$tmp" && { echo "update_readme_ports: README.md already up to date"; exit 0; }
chmod --reference=README.md "$tmp"
mv "$tmp" README.md
trap - EXIT
echo "update_readme_ports: README.md port table rewritten"
