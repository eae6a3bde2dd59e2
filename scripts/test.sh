#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs what is missing, builds, and runs the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
# Without arguments: the default suite, which leaves out the tests labelled "long" (the slow proofs and
# X-propagation runs, ctest -L formal runs them; docs/formal.md). With arguments: exactly what is asked.
if [ $# -eq 0 ]; then set -- -LE long; fi
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" "$@"
