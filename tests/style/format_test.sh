#!/usr/bin/env bash
# The C++ sources are as clang-format (.clang-format) writes them: lists every file it would
# change. Usage: format_test.sh SOURCE_DIR
set -euo pipefail
cd "$1"
mapfile -t files < <(find server client tests -name '*.cc' -o -name '*.h' | sort)
[ "${#files[@]}" -gt 100 ] || { echo "format_test: only ${#files[@]} C++ files found" >&2; exit 1; }
if ! clang-format --dry-run --Werror "${files[@]}" 2>"${TMPDIR:-/tmp}/format_test.$$"; then
  grep -o '^[^:]*:' "${TMPDIR:-/tmp}/format_test.$$" | sort -u | sed 's/:$//; s/^/  /' >&2
  rm -f "${TMPDIR:-/tmp}/format_test.$$"
  echo "format_test: the files above are not formatted; run clang-format -i on them" >&2
  exit 1
fi
rm -f "${TMPDIR:-/tmp}/format_test.$$"
echo "format_test: ${#files[@]} files formatted"
