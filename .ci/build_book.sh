#!/usr/bin/env bash
# Build the segplan book (book/) offline, executing every notebook.
#
#   .ci/build_book.sh              install what the book needs (idempotent), then build
#   PYTHON=/path/to/python .ci/build_book.sh
#
# Installs, only when missing:
#   * MathJax 3 (npm package "mathjax", pinned version and integrity) into book/_vendor/mathjax;
#     Sphinx copies it into book/_build/html/_static/mathjax, so the pages load no CDN.
#     Needs npm once (Debian package "npm" is installed with apt-get when npm is absent).
#   * Debian's "chromium", used by tests/test_book.py to open the built pages
#     (skipped with BOOK_SKIP_BROWSER=1).
# Builds with `jupyter-book build book --all -W --keep-going -n`: any warning (a Sphinx warning,
# a broken reference, a cell error or anything a cell writes to stderr) fails the build.
# The build itself downloads nothing.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PYTHON="${PYTHON:-$(command -v python3)}"
MATHJAX_VERSION="3.2.2"
MATHJAX_INTEGRITY="sha512-Bt+SSVU8eBG27zChVewOicYs7Xsdt40qm4+UpHyX7k0/O9NliPc+x77k1/FEsPsjKPZGJvtRZM1vO+geW0OhGw=="
VENDOR="$ROOT/book/_vendor"
APT_UPDATED=0

log() { printf '[build_book] %s\n' "$*"; }

apt_install() {
    if [ "$(id -u)" != 0 ]; then
        log "need Debian package(s) $* but not running as root: install them with apt-get"
        return 1
    fi
    if [ "$APT_UPDATED" = 0 ]; then
        DEBIAN_FRONTEND=noninteractive apt-get update -qq
        APT_UPDATED=1
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

ensure_mathjax() {
    local dest="$VENDOR/mathjax"
    if [ -f "$dest/tex-mml-chtml.js" ] && [ "$(cat "$dest/.version" 2>/dev/null)" = "$MATHJAX_VERSION" ]; then
        log "MathJax $MATHJAX_VERSION already in book/_vendor/mathjax"
        return
    fi
    command -v npm >/dev/null || apt_install npm
    local tmp
    tmp="$(mktemp -d)"
    trap 'rm -rf "$tmp"; trap - RETURN' RETURN
    log "fetching MathJax $MATHJAX_VERSION with npm pack"
    (cd "$tmp" && npm pack --silent "mathjax@$MATHJAX_VERSION" >/dev/null)
    local tarball="$tmp/mathjax-$MATHJAX_VERSION.tgz"
    local got
    got="$("$PYTHON" -c 'import base64, hashlib, sys
print("sha512-" + base64.b64encode(hashlib.sha512(open(sys.argv[1], "rb").read()).digest()).decode())' "$tarball")"
    if [ "$got" != "$MATHJAX_INTEGRITY" ]; then
        log "MathJax tarball integrity mismatch: got $got"
        exit 1
    fi
    tar -xzf "$tarball" -C "$tmp"
    # Keep the tex-mml-chtml component and everything it may load lazily (input/, output/
    # with its fonts, ui/, a11y/, sre/, adaptors/); leave out the other combined bundles
    # and latest.js (which would fetch a CDN copy).
    local es5="$tmp/package/es5"
    rm -f "$es5"/{tex-chtml,tex-chtml-full,tex-chtml-full-speech,tex-svg,tex-svg-full,tex-mml-svg,mml-chtml,mml-svg,node-main,latest}.js
    cp "$tmp/package/LICENSE" "$es5/LICENSE"
    echo "$MATHJAX_VERSION" >"$es5/.version"
    mkdir -p "$VENDOR"
    rm -rf "$dest"
    mv "$es5" "$dest"
    log "MathJax $MATHJAX_VERSION installed in book/_vendor/mathjax ($(du -sh "$dest" | cut -f1))"
}

ensure_chromium() {
    if [ "${BOOK_SKIP_BROWSER:-0}" = 1 ] || command -v chromium >/dev/null; then
        return
    fi
    log "installing Debian's chromium (for tests/test_book.py)"
    apt_install chromium || log "chromium not installed: tests/test_book.py will not run"
}

build() {
    cd "$ROOT"
    rm -rf book/_build
    log "building the book with $PYTHON"
    local start=$SECONDS
    "$PYTHON" -c 'import sys
from jupyter_book.cli.main import main
sys.argv[0] = "jupyter-book"
sys.exit(main())' build book --all -W --keep-going -n
    log "book built in $((SECONDS - start)) s: book/_build/html/index.html"
}

ensure_mathjax
ensure_chromium
build
