#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Runs a tool that must refuse to elaborate an illegal parameter setting:
#
#   rtl/tests/expect_elab_error.sh MESSAGE TOOL [ARGS...]
#
# PASS (exit 0) only if TOOL exits non-zero AND its output names MESSAGE (the undefined module a
# failing parameter check instantiates, e.g. sc_cs16_error_illegal_FRAC_legal_range_is_8_to_24).
# A tool that prints the message but exits 0 (a warning, not an error) or fails for another reason
# is a FAIL. (ctest's PASS_REGULAR_EXPRESSION alone ignores the exit status, hence this wrapper.)
set -u
msg="$1"; shift
out=$("$@" 2>&1); rc=$?
if [ $rc -ne 0 ] && printf '%s\n' "$out" | grep -q -F -- "$msg"; then
  echo "expect_elab_error: PASS: $1 stopped elaboration (status $rc) with $msg"
  exit 0
fi
printf '%s\n' "$out" | tail -20
echo "expect_elab_error: FAIL: $1 exited with status $rc; expected a non-zero status and '$msg'"
exit 1
