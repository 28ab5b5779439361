#!/usr/bin/env bash
# clang-tidy (.clang-tidy) on the C++ files of server/ and client/ the last commits changed
# (at most KERF_TIDY_MAX_FILES, default 12, newest first; a changed header brings its .cc), so
# that the check fits in the test command's time; `scripts/tidy` runs it on every file. The
# compile commands are the build's own, without gcc's precompiled header and gcc-only warning
# flags, which clang cannot read. Usage: tidy_test.sh SOURCE_DIR BINARY_DIR [COMMITS]
set -euo pipefail
src=$1
bin=$2
commits=${3:-5}
max=${KERF_TIDY_MAX_FILES:-12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

sed -e 's/-include [^ ]*cmake_pch\.hxx//g' -e 's/-Winvalid-pch//g' \
  -e 's/-Wno-stringop-overflow//g' -e 's/-Wno-stringop-overread//g' \
  "$bin/compile_commands.json" >"$work/compile_commands.json"

if [ -n "${KERF_TIDY_ALL:-}" ]; then
  mapfile -t files < <(cd "$src" && find server client -name '*.cc' | sort)
else
  if ! git -C "$src" rev-parse --verify -q "HEAD~$commits" >/dev/null; then
    commits=$(($(git -C "$src" rev-list --count HEAD) - 1))
  fi
  mapfile -t files < <(
    cd "$src" &&
      git log --name-only --format= "HEAD~$commits..HEAD" -- server client |
      sed -E 's/\.h$/.cc/' | awk '!seen[$0]++' | while read -r f; do
        [ -f "$f" ] && case $f in *.cc) echo "$f" ;; esac
      done | head -n "$max"
  )
fi
if [ "${#files[@]}" -eq 0 ]; then
  echo "tidy_test: no C++ file of server/ or client/ changed in the last $commits commits"
  exit 0
fi
echo "tidy_test: ${#files[@]} files: ${files[*]}"
cd "$src"
printf '%s\n' "${files[@]}" |
  xargs -P 2 -n 1 clang-tidy -p "$work" --quiet >"$work/out" 2>&1 || {
  grep -E "(warning|error):" "$work/out" >&2 || cat "$work/out" >&2
  echo "tidy_test: clang-tidy found the above" >&2
  exit 1
}
echo "tidy_test: clean"
