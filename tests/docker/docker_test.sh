#!/usr/bin/env bash
# No Docker engine runs here, so this checks what can be checked without one:
#   1. docker/Dockerfile builds on bookworm and runs on bookworm-slim, and installs packages
#      only through scripts/setup (--image-build to build, --runtime to run), builds the web
#      viewer and serves it on its HTTP port;
#   2. every shared library the binaries it copies load belongs to a runtime package of
#      scripts/packages.txt (or to the slim image's own libc6, libgcc-s1, zlib1g);
#   3. the image's command, with certificates from docker/make-certs, serves TLS and its health
#      check (kerf-health, as the Dockerfile and compose.yaml call it) answers SERVING;
#   4. compose.yaml has the server with its health check and a load-test profile.
# Usage: docker_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
fail() { echo "docker_test: $*" >&2; exit 1; }

dockerfile=$src/docker/Dockerfile
grep -q '^FROM debian:bookworm AS build$' "$dockerfile" || fail "build stage is not debian:bookworm"
grep -q '^FROM debian:bookworm-slim$' "$dockerfile" || fail "runtime stage is not debian:bookworm-slim"
grep -q '^RUN scripts/setup --image-build$' "$dockerfile" ||
  fail "build stage does not run scripts/setup --image-build"
grep -q 'cd web && npm ci' "$dockerfile" || fail "build stage does not build the web viewer"
grep -q 'COPY --from=build /src/web/dist' "$dockerfile" || fail "the image lacks the web viewer"
grep -q '^EXPOSE 50051 8080$' "$dockerfile" || fail "the image does not expose gRPC and HTTP"
grep -q -- '--http_listen=0.0.0.0:8080' "$dockerfile" || fail "the image's server has no HTTP port"
grep -q '^RUN /opt/kerf/scripts/setup --runtime' "$dockerfile" ||
  fail "runtime stage does not run scripts/setup --runtime"
! grep -Eq 'apt-get|apt install|dpkg -i' "$dockerfile" || fail "Dockerfile installs packages itself"
grep -q 'scripts/packages.txt' "$dockerfile" || fail "Dockerfile does not copy scripts/packages.txt"

runtime=$(grep '^runtime ' "$src/scripts/packages.txt" | cut -d' ' -f2)
allowed=" $(echo $runtime) libc6 libgcc-s1 zlib1g "  # the last three are in the slim image
libs=()
# find -print -quit, not | head -1: under pipefail, find cut off by head's exit (SIGPIPE) failed
# the script now and then, silently.
for name in kerf-server kerf kerf-load kerf-haptic kerf-script kerf-health; do
  grep -Eq "/$name( |\\|$)" "$dockerfile" || fail "Dockerfile does not copy $name"
  binary=$(find "$bin" -type f -name "$name" -perm -u+x -print -quit)
  [ -n "$binary" ] || fail "no built $name under $bin"
  libs+=($(ldd "$binary" | awk '/=>/ {print $3}'))
done
# One dpkg query for them all; a library may be listed under /lib or /usr/lib (usrmerge).
owners=$(for lib in $(printf '%s\n' "${libs[@]}" | sort -u); do echo "$lib"; echo "/usr$lib"; done |
         xargs dpkg -S 2>/dev/null | sed 's|: /usr/|: /|' || true)
for lib in $(printf '%s\n' "${libs[@]}" | sort -u); do
  # From a here-string, not `echo | awk`: awk's exit at its match while echo still wrote (the
  # owners run past one 4 KB write) killed echo (SIGPIPE) and, under pipefail, the script.
  package=$(awk -v lib="${lib#/usr}" '$2 == lib {sub(/:.*/, "", $1); print $1; exit}' <<<"$owners")
  [ -n "$package" ] || fail "$lib, loaded by a binary of the image, is owned by no package"
  [[ "$allowed" == *" $package "* ]] ||
    fail "$lib comes from $package, which is not a runtime package in scripts/packages.txt"
done

certs=$(mktemp -d)
trap 'kill "$server" 2>/dev/null || true; rm -rf "$certs"' EXIT
"$src/docker/make-certs" "$certs" >/dev/null
log=$certs/server.log
"$(find "$bin" -type f -name kerf-server -print -quit)" --listen=127.0.0.1:0 --http_listen= --journal_dir="$certs/journal" \
  --tls_cert="$certs/server.pem" --tls_key="$certs/server.key" >"$log" 2>&1 &
server=$!
for _ in $(seq 100); do grep -q "listening on" "$log" 2>/dev/null && break; sleep 0.1; done
address=$(sed -n 's/^kerf-server listening on //p' "$log")
[ -n "$address" ] || fail "kerf-server with TLS did not start: $(cat "$log")"
health=$(find "$bin" -type f -name kerf-health -print -quit)
# Under the sanitizers: gRPC's exit race with OpenSSL's per-thread state is not kerf's leak.
export LSAN_OPTIONS="suppressions=$src/tests/support/lsan_grpc_openssl_exit.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# Its answer read whole, then matched: `| grep -q` under pipefail fails now and then, when grep
# has matched and gone before kerf-health's last write (SIGPIPE).
answer=$("$health" --server="$address" --tls_ca="$certs/ca.pem") ||
  fail "kerf-health over TLS failed: $answer"
grep -q SERVING <<<"$answer" || fail "kerf-health over TLS did not answer SERVING: $answer"
! "$health" --server="$address" --timeout_seconds=2 >/dev/null 2>&1 ||
  fail "kerf-health without the CA was answered"

compose=$src/docker/compose.yaml
grep -q 'kerf-health' "$compose" || fail "compose.yaml has no kerf-health health check"
grep -q 'profiles: \[load\]' "$compose" || fail "compose.yaml has no load profile"
grep -q '"50051:50051"' "$compose" || fail "compose.yaml does not publish the gRPC port"
grep -q '"127.0.0.1:8080:8080"' "$compose" || fail "compose.yaml does not publish the HTTP port on loopback"
grep -q '^build nodejs node$' "$src/scripts/packages.txt" || fail "packages.txt lacks Node.js"
echo "docker_test: ok"
