#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The house rules a script can check (issue 20): every source file carries an SPDX line in its first three
# lines; no source includes another layer's folder by a relative path (../sim, ../cli); at most 8 headers
# directly in cmodel/include/shadecore/ (the rest by role in units/, analysis/, render/).
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"
fail=0
while IFS= read -r -d '' f; do
  if ! head -n 3 "$f" | grep -q 'SPDX-License-Identifier: Apache-2.0'; then
    echo "check_house: no SPDX line: $f"; fail=1
  fi
done < <(find cli cmodel common stimulus sim rtl tests bench scripts cmake handoff formal .ci CMakeLists.txt \
           -path tests/data -prune -o -type f \
           \( -name '*.cpp' -o -name '*.hpp' -o -name '*.v' -o -name '*.vh' -o -name '*.vlt' -o -name '*.sh' \
              -o -name '*.py' -o -name '*.cmake' -o -name CMakeLists.txt -o -name run \) -print0)
if grep -rn --include='*.cpp' --include='*.hpp' '\.\./sim\|\.\./cli' cli cmodel common stimulus sim tests bench; then
  echo "check_house: a source includes another layer's folder by a relative path"; fail=1
fi
n=$(find cmodel/include/shadecore -maxdepth 1 -name '*.hpp' | wc -l)
if [ "$n" -gt 8 ]; then echo "check_house: $n headers directly in cmodel/include/shadecore (at most 8)"; fail=1; fi
[ -f LICENSE ] && grep -q 'Apache License' LICENSE || { echo "check_house: no Apache-2.0 LICENSE"; fail=1; }
[ "$fail" = 0 ] && echo "check_house: PASS"
exit "$fail"
