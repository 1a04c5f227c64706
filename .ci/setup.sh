#!/usr/bin/env bash
# Create (or update) the project's virtual environment with the pinned dependencies, and the
# browser the book's test uses. Sourced by .ci/book; works on a fresh machine with Python >= 3.11.
#
# The environment (environment.txt, then segplan itself, editable) is all the book build needs.
# Debian's chromium is for tests/test_book.py only: installed with apt-get when missing and
# running as root (skip with BOOK_SKIP_BROWSER=1; without it that test skips).
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
"$VENV/bin/python" -c 'import segplan, numpy, scipy, sympy, shapely, nbval, hypothesis, jupyter_book' \
    || { echo "setup failed: dependencies missing in $VENV" >&2; exit 1; }
"$VENV/bin/python" -c 'import importlib.util, sys; sys.exit(importlib.util.find_spec("sphinx-mathjax-offline") is None)' \
    || { echo "setup failed: sphinx-mathjax-offline (the book's MathJax) missing in $VENV" >&2; exit 1; }

if [ "${BOOK_SKIP_BROWSER:-0}" != 1 ] && ! command -v chromium >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ]; then
        echo "[setup] installing Debian's chromium (for tests/test_book.py)"
        DEBIAN_FRONTEND=noninteractive apt-get update -qq &&
            DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null ||
            echo "[setup] chromium not installed: tests/test_book.py will skip its browser checks"
    else
        echo "[setup] chromium missing and not root: install Debian's chromium for tests/test_book.py"
    fi
fi
export PATH="$PWD/$VENV/bin:$PATH"
