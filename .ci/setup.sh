#!/usr/bin/env bash
# Create (or update) the project's virtual environment with the pinned dependencies.
# Sourced by .ci/book; works on a fresh machine with Python >= 3.11.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
VENV=${SEGPLAN_VENV:-.venv}
if [ ! -x "$VENV/bin/python" ]; then
    PY=""
    for cand in python3.11 python3.12 python3.13 python3; do
        if command -v "$cand" >/dev/null 2>&1 &&
            "$cand" -c 'import sys; sys.exit(sys.version_info < (3, 11))'; then
            PY=$cand
            break
        fi
    done
    [ -n "$PY" ] || { echo "segplan needs Python >= 3.11" >&2; exit 1; }
    "$PY" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install -q --disable-pip-version-check -r environment.txt 2>&1 | grep -v "is ignored" || true
"$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e . 2>&1 | grep -v "is ignored" || true
"$VENV/bin/python" -c 'import segplan, numpy, scipy, sympy, shapely, nbval, hypothesis' \
    || { echo "setup failed: dependencies missing in $VENV" >&2; exit 1; }
export PATH="$PWD/$VENV/bin:$PATH"
