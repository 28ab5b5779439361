#!/usr/bin/env bash
# Runs the README's shell blocks marked `<!-- readme-test -->` (or `<!-- readme-test: expect
# TEXT -->`, and then checks that the block printed TEXT), as a newcomer would type them, so
# that they stay true. The binaries come from BINARY_DIR (the README names build/default), the
# ports 50051 and 8080 become free ones, and /tmp/kerf-readme- files go to a directory of the
# test's own. Usage: readme_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
nl=$'\n'
fail() {
  echo "readme_test: $*" >&2
  exit 1
}

# A loopback port nobody listens on (bash's /dev/tcp connects where someone does).
free_port() {
  local port
  while :; do
    port=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || break
  done
  echo "$port"
}

# Block n goes to $work/block_n.sh, what it must print to $work/expect_n.
awk -v dir="$work" '
  /^<!-- readme-test(: expect .*)? -->$/ {
    marked = 1; ++n
    expect = $0; sub(/^<!-- readme-test(: expect )?/, "", expect); sub(/ ?-->$/, "", expect)
    printf "%s", expect > (dir "/expect_" n)
    next
  }
  marked && /^```sh$/ { inside = 1; marked = 0; next }
  inside && /^```$/ { inside = 0; next }
  inside { print > (dir "/block_" n ".sh") }
' "$src/README.md"
blocks=$(find "$work" -name 'block_*.sh' | wc -l)
[ "$blocks" -ge 2 ] || fail "the README has $blocks tested shell blocks; expected at least 2"

for ((n = 1; n <= blocks; ++n)); do
  grpc=$(free_port)
  http=$(free_port)
  {
    # A block that fails half way leaves no server behind.
    echo "trap 'kill \$(jobs -p) 2>/dev/null || true' EXIT"
    sed -e "s|build/default/|$bin/|g" -e "s|127\.0\.0\.1:50051|127.0.0.1:$grpc|g" \
      -e "s|127\.0\.0\.1:8080|127.0.0.1:$http|g" -e "s|/tmp/kerf-readme-|$work/|g" \
      "$work/block_$n.sh"
  } >"$work/run_$n.sh"
  echo "readme_test: block $n"
  sed 's/^/  /' "$work/block_$n.sh"
  (cd "$src" && timeout 300 bash -euo pipefail "$work/run_$n.sh") >"$work/out_$n" 2>&1 ||
    fail "block $n failed (exit $?):${nl}$(cat "$work/out_$n")"
  expect=$(cat "$work/expect_$n")
  if [ -n "$expect" ] && ! grep -qF -- "$expect" "$work/out_$n"; then
    fail "block $n did not print \"$expect\":${nl}$(cat "$work/out_$n")"
  fi
done
echo "readme_test: $blocks blocks ran as written"
