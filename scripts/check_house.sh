#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The house rules a script can check (issue 20): every source file carries an SPDX line in its first three
# lines (templates of cli/templates/: in their first line); no source includes another layer's folder by a
# relative path (../sim, ../cli) and no target's include directories name another folder; at most 8 headers
# directly in cmodel/include/shadecore/ (the rest by role in units/, analysis/, render/).
# Usage: check_house.sh [SOURCE_DIR [BUILD_DIR]] (BUILD_DIR: also check its compile_commands.json).
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"
fail=0
while IFS= read -r -d '' f; do
  if ! head -n 3 "$f" | grep -q 'SPDX-License-Identifier: Apache-2.0'; then
    echo "check_house: no SPDX line: $f"; fail=1
  fi
done < <(find cli cmodel common driver stimulus sim rtl tests bench scripts cmake handoff formal signoff python .ci CMakeLists.txt \
           -path tests/data -prune -o -type f \
           \( -name '*.cpp' -o -name '*.hpp' -o -name '*.v' -o -name '*.vh' -o -name '*.vlt' -o -name '*.sh' \
              -o -name '*.py' -o -name '*.cmake' -o -name CMakeLists.txt -o -name run -o -name '*.c' -o -name '*.h' \) -print0)
if grep -rn --include='*.cpp' --include='*.hpp' --include='*.c' --include='*.h' '\.\./sim\|\.\./cli' cli cmodel common driver stimulus sim tests bench python; then
  echo "check_house: a source includes another layer's folder by a relative path"; fail=1
fi
# Templates compiled into the CLI (cli/templates/): the SPDX line is their first line (cmake/EmbedTemplates.cmake
# drops it from the text).
if [ -d cli/templates ]; then
  while IFS= read -r -d '' f; do
    head -n 1 "$f" | grep -q 'SPDX-License-Identifier: Apache-2.0' || { echo "check_house: no SPDX first line: $f"; fail=1; }
  done < <(find cli/templates -type f -print0)
fi
# A target's include directories name its own folder (or generated ones), never another layer's source
# folder (sim/light_core is a separate CMake project that consumes the libraries' public include folders).
while IFS= read -r f; do
  bad=$(awk '/target_include_directories\(/ { on = 1 } on { print FILENAME ":" FNR ": " $0 } on && /\)/ { on = 0 }' "$f" |
        grep -E 'CMAKE_SOURCE_DIR\}/|SHADECORE_SOURCE_DIR\}/|\.\./' || true)
  if [ -n "$bad" ]; then echo "$bad"; echo "check_house: an include path names another folder: $f"; fail=1; fi
done < <(find . -name CMakeLists.txt -not -path './build*' -not -path './sim/light_core/*')
# With a build directory: every compile command's -I paths are the source's own folder, a library's public
# include folder (<lib>/include), generated or build folders, or outside the tree (compile_commands.json).
if [ -n "${2:-}" ] && [ -f "$2/compile_commands.json" ]; then
  python3 - "$PWD" "$2/compile_commands.json" <<'EOF' || fail=1
import json, os, re, shlex, sys
root, db = os.path.realpath(sys.argv[1]), sys.argv[2]
bad = set()
for e in json.load(open(db)):
    src = os.path.realpath(os.path.join(e["directory"], e["file"]))
    if not src.startswith(root + "/") or "/build" in src[len(root):]:
        continue  # generated (Verilated) sources live in the build tree
    own = os.path.relpath(src, root).split("/")[0]
    args = e.get("arguments") or shlex.split(e["command"])
    incs = [a[2:] for a in args if a.startswith("-I") and len(a) > 2]
    incs += [args[i + 1] for i, a in enumerate(args[:-1]) if a in ("-I", "-isystem")]
    for inc in incs:
        d = os.path.realpath(os.path.join(e["directory"], inc))
        if not d.startswith(root + "/") or "/build" in d[len(root):]:
            continue
        rel = os.path.relpath(d, root)
        top = rel.split("/")[0]
        if top != own and not re.fullmatch(r"[^/]+/include", rel):
            bad.add(f"{os.path.relpath(src, root)}: -I {rel}")
for b in sorted(bad):
    print("check_house: include path of another layer's folder:", b)
sys.exit(1 if bad else 0)
EOF
fi
n=$(find cmodel/include/shadecore -maxdepth 1 -name '*.hpp' | wc -l)
if [ "$n" -gt 8 ]; then echo "check_house: $n headers directly in cmodel/include/shadecore (at most 8)"; fail=1; fi
[ -f LICENSE ] && grep -q 'Apache License' LICENSE || { echo "check_house: no Apache-2.0 LICENSE"; fail=1; }
[ "$fail" = 0 ] && echo "check_house: PASS"
exit "$fail"
