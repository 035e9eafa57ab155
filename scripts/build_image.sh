#!/usr/bin/env bash
# `make image`: build the course's image (Dockerfile) with docker, or podman where docker has
# no engine. IMAGE names it (ros2-params-course:dev), TARGET picks a stage (course; singleuser
# is deploy/kubernetes/'s learners' image), NO_CACHE=1 builds every layer again.
set -euo pipefail
cd "$(dirname "$0")/.."
image="${IMAGE:-ros2-params-course:dev}"
target="${TARGET:-course}"
fresh=()
[ -z "${NO_CACHE:-}" ] || fresh=(--no-cache)

if command -v docker >/dev/null && docker info >/dev/null 2>&1; then
  exec docker build "${fresh[@]}" --target "$target" -t "$image" .
fi
if ! command -v podman >/dev/null; then
  echo "make image needs docker (with its engine running) or podman: install one of them." >&2
  exit 1
fi
extra=()
# The build's pip and uv trust what this machine trusts (PIP_CERT's or SSL_CERT_FILE's bundle,
# else the system's): a network that re-signs TLS works in the build as it does here. The
# bundle is mounted for the build only, never copied into the image.
bundle="${PIP_CERT:-${SSL_CERT_FILE:-/etc/ssl/certs/ca-certificates.crt}}"
if [ -n "$bundle" ] && [ -f "$bundle" ]; then
  extra+=(-v "$bundle:/run/host-ca.pem:ro" --build-arg PIP_CERT=/run/host-ca.pem
          --build-arg SSL_CERT_FILE=/run/host-ca.pem)
fi
# uv's package cache, lent to the build: what `make setup` downloaded is not downloaded again.
cache="${UV_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/uv}"
mkdir -p "$cache"
extra+=(-v "$cache:/run/uv-cache" --build-arg UV_CACHE_DIR=/run/uv-cache)
exec podman build --isolation chroot --network host --layers "${fresh[@]}" --target "$target" \
  -t "$image" "${extra[@]}" .
