#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Bad waveform outputs of `shadecore cosim --core lighting --trace` (issue 36) are refused before anything
# is built or run, with one line on stderr and exit 1, and nothing is left behind: a directory that does not
# exist, a FIFO, a symlink into a missing directory, a directory; --trace-all / --trace-window without
# --trace, both together, or with the specular core. Usage: light_trace_bad.sh SHADECORE
set -u
sc=$1
d=light_trace_bad
rm -rf "$d"
mkdir "$d"
mkfifo "$d/fifo.fst"
ln -s "$PWD/$d/missing/w.fst" "$d/dangling.fst"
mkdir "$d/adir"
fails=0
refuse() {  # refuse PATTERN ARGS...: exit 1, one line on stderr matching PATTERN, nothing on stdout
  pat=$1; shift
  "$sc" cosim "$@" >"$d/.out" 2>"$d/.err" </dev/null
  rc=$?
  n=$(wc -l <"$d/.err")
  if [ $rc -ne 1 ] || [ "$n" -ne 1 ] || ! grep -q -e "$pat" "$d/.err" || [ -s "$d/.out" ]; then
    echo "FAIL: cosim $* -> exit $rc, stderr:"; cat "$d/.err"; echo "stdout:"; cat "$d/.out"; fails=1
  else
    echo "ok: $(cat "$d/.err")"
  fi
}
L="--core lighting --features diffuse --mode random --count 100"
refuse "no directory" $L --trace "$d/missing/w.fst"
refuse "device or FIFO" $L --trace "$d/fifo.fst"
refuse "no directory" $L --trace "$d/dangling.fst"
refuse "is a directory" $L --trace "$d/adir"
refuse "need --trace FILE" $L --trace-all
refuse "need --trace FILE" $L --trace-window 10
refuse "one or the other" $L --trace "$d/w.fst" --trace-all --trace-window 10
refuse "trace-window" $L --trace "$d/w.fst" --trace-window 0
refuse "need --core lighting" --trace-all --trace "$d/w.fst"
refuse "not both" $L --trace "$d/w.fst" --trace-all --coverage "$d/cov"
rm -f "$d/.out" "$d/.err"
left=$(ls -A "$d" | grep -v -x -e fifo.fst -e dangling.fst -e adir || true)
[ -z "$left" ] || { echo "FAIL: left behind: $left"; fails=1; }
[ -z "$(ls -A "$d/adir")" ] || { echo "FAIL: written into adir"; fails=1; }
[ -p "$d/fifo.fst" ] && [ -L "$d/dangling.fst" ] || { echo "FAIL: the FIFO or the link was replaced"; fails=1; }
[ $fails -eq 0 ] && echo "light_trace_bad: PASS"
exit $fails
