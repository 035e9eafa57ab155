#!/usr/bin/env bash
# Set up podman for the image checks (tests/browser/test_course_image.py) on a CI machine
# with no image registry: runc (crun fails here: "cgroups in hybrid mode not supported"),
# process and file limits no higher than the machine's hard limits (the VM refuses to raise
# RLIMIT_NPROC), and the Dockerfile's base image made from Debian's packages under the
# official image's name, so the Dockerfile stays the one a learner builds anywhere.
set -euo pipefail
[ "$(id -u)" -eq 0 ] || exec sudo "$0" "$@"
base="docker.io/library/debian:bookworm-slim"

limit() { local hard="$1"; [ "$hard" = unlimited ] || [ "$hard" -gt "$2" ] && echo "$2" || echo "$hard"; }
nproc=$(limit "$(ulimit -Hu)" 32768)
nofile=$(limit "$(ulimit -Hn)" 20000)
conf=/etc/containers/containers.conf
if ! grep -qs 'ros2-params-course' "$conf"; then
  mkdir -p "$(dirname "$conf")"
  cat > "$conf" <<CONF
# Written by the ros2-params-course CI (.ci/container_engine.sh)
[containers]
default_ulimits = ["nproc=$nproc:$nproc", "nofile=$nofile:$nofile"]
[engine]
runtime = "runc"
CONF
fi

if ! podman image exists "$base"; then
  sources=/etc/apt/sources.list.d/debian.sources
  [ -f "$sources" ] || sources=/etc/apt/sources.list
  tarball=$(mktemp --suffix=.tar)
  mmdebstrap --variant=minbase --quiet bookworm "$tarball" - < "$sources"
  podman import --quiet "$tarball" "$base" >/dev/null
  rm -f "$tarball"
fi
