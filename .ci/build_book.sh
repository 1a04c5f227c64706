#!/usr/bin/env bash
# Build the segplan book (book/) offline, executing every notebook.
#
#   .ci/build_book.sh              PYTHON=/path/to/python .ci/build_book.sh
#
# Runs `jupyter-book build book --all -W --keep-going -n` from a clean book/_build: any warning
# (a Sphinx warning, a broken reference, a cell error or anything a cell writes to stderr)
# fails the build. It needs only the Python environment of environment.txt (MathJax comes
# from the package sphinx-mathjax-offline): no npm, no apt, no network. Plain
# `jupyter-book build book` works as well, without the strictness. Every chapter is executed
# afresh, two at a time (book/_ext/segplan_execute.py); the log gives each one's time.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PYTHON="${PYTHON:-$(command -v python3)}"

log() { printf '[build_book] %s\n' "$*"; }

cd "$ROOT"
rm -rf book/_build
log "building the book with $PYTHON"
start=$SECONDS
"$PYTHON" -c 'import sys
from jupyter_book.cli.main import main
sys.argv[0] = "jupyter-book"
sys.exit(main())' build book --all -W --keep-going -n
log "book built in $((SECONDS - start)) s: book/_build/html/index.html"
