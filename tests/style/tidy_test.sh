#!/usr/bin/env bash
# clang-tidy (.clang-tidy) on the C++ files of server/ and client/ changed most recently (the
# newest KERF_TIDY_MAX_FILES, default 12; a changed header brings its .cc), so that the check
# fits in the test command's time; `scripts/tidy` runs it on every file. The compile commands
# are the build's own, without gcc's precompiled header and gcc-only warning flags, which clang
# cannot read. Usage: tidy_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
max=${KERF_TIDY_MAX_FILES:-12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

sed -e 's/-include [^ ]*cmake_pch\.hxx//g' -e 's/-Winvalid-pch//g' \
  -e 's/-Wno-stringop-overflow//g' -e 's/-Wno-stringop-overread//g' \
  "$bin/compile_commands.json" >"$work/compile_commands.json"

if [ -n "${KERF_TIDY_ALL:-}" ]; then
  mapfile -t files < <(cd "$src" && find server client -name '*.cc' | sort)
else
  if ! git -C "$src" rev-parse --verify -q HEAD >/dev/null 2>&1; then
    echo "tidy_test: $src has no git history to find changed files in; scripts/tidy checks them all"
    exit 0
  fi
  # The most recently changed .cc files (a changed header stands for its .cc), newest first.
  mapfile -t files < <(
    cd "$src" &&
      git log --name-only --format= -- server client |
      sed -E 's/\.h$/.cc/' | awk '!seen[$0]++' | while read -r f; do
        [ -f "$f" ] && case $f in *.cc) echo "$f" ;; esac
      done | head -n "$max"
  )
fi
[ "${#files[@]}" -gt 0 ] || { echo "tidy_test: no C++ file of server/ or client/ found" >&2; exit 1; }
echo "tidy_test: ${#files[@]} files: ${files[*]}"
cd "$src"
printf '%s\n' "${files[@]}" |
  xargs -P 2 -n 1 clang-tidy -p "$work" --quiet >"$work/out" 2>&1 || {
  grep -E "(warning|error):" "$work/out" >&2 || cat "$work/out" >&2
  echo "tidy_test: clang-tidy found the above" >&2
  exit 1
}
echo "tidy_test: clean"
