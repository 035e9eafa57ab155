#!/usr/bin/env bash
# Prove one more supported interpreter: a fresh venv, environment.txt, then a short smoke test
# (import rclpy, one node in its own domain, a few MuJoCo steps of the course's robot).
#
# Usage: scripts/smoke_python.sh [PYTHON]   (default: CPython 3.12 via pyenv, else python3.12)
# Exits 0 with a note when no such interpreter is installed; never touches .venv/.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"

if [ $# -gt 0 ]; then
  python=("$1")
elif command -v pyenv >/dev/null && pyenv versions --bare 2>/dev/null | grep -qx '3.12.1'; then
  python=(env PYENV_VERSION=3.12.1 python)
elif command -v python3.12 >/dev/null; then
  python=(python3.12)
else
  echo "smoke_python: no CPython 3.12 here (pyenv 3.12.1 or python3.12); nothing proven." >&2
  exit 0
fi

started=$(date +%s)
venv="$(mktemp -d)"
trap 'rm -rf "$venv"' EXIT
"${python[@]}" "$repo/scripts/check_platform.py"
"${python[@]}" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$repo/environment.txt" \
  2> >(grep -v '^WARNING: Location' >&2)  # pip's notes on configured local indexes
cd "$repo"
PYTHONPATH="$repo" "$venv/bin/python" scripts/smoke_python.py
echo "smoke_python: $("$venv/bin/python" --version) passed in $(( $(date +%s) - started )) s"
