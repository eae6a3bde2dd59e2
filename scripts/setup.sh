#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the Debian packages shadecore needs, if any are missing. Idempotent and quiet when
# everything is present. Needs root (or sudo) only when something must be installed.
# Extra package names given as arguments are installed too (scripts/cost_report.py asks for the
# iCE40 place-and-route tools this way, so the default setup stays lean). z3 (the SMT solver of
# yosys-smtbmc), sollya and gappa are the proof tools of the formal suite (docs/formal.md, docs/bounds.md).
# libosmesa6-dev (Mesa's off-screen GL, llvmpipe) with the GL headers (libgl-dev: GL/gl.h, mesa-common-dev) is
# the outside reference of `shadecore gl-compare` (docs/gl_compare.md). qflow-tech-osu018 (the OSU 0.18 um cell
# library) and opensta (OpenSTA) are the timing and energy sign-off (signoff/, docs/signoff.md). apitrace,
# mesa-utils (glxgears), xvfb with xauth (xvfb-run) and libsnappy-dev (the capture reader's decompressor) are
# `shadecore replay` (docs/replay.md); `scripts/setup.sh xscreensaver-gl` adds the programs of its table.
# lcov (genhtml) turns the merged Verilator coverage into HTML (`regress --coverage`, docs/coverage.md).
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libtinyobjloader-dev
  verilator libsystemc-dev yosys iverilog lcov
  z3 sollya gappa
  libosmesa6-dev libgl-dev mesa-common-dev
  python3 python3-numpy python3-matplotlib zlib1g-dev
  python3-dev python3-pybind11 python3-pytest
  slurm-wlm munge
  qflow-tech-osu018 opensta
  apitrace mesa-utils xvfb xauth libsnappy-dev
  "$@"
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
