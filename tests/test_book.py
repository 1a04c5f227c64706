"""The built book stands alone: every page opened in headless Chromium with no network.

Checks on ``book/_build/html`` (built by ``.ci/build_book.sh``):

* every notebook in ``notebooks/`` is a chapter of the book;
* internal links and resources resolve (files exist, ``#anchors`` exist in their page) and no
  page loads a script, stylesheet, image or frame from another host;
* in Chromium (Debian's ``chromium``, installed by ``.ci/setup.sh``, driven through the DevTools
  protocol over a pipe, standard library only): no broken image, every math element rendered
  by the shipped MathJax (an ``mjx-container`` inside, no ``mjx-merror``), no raw TeX
  delimiters left in the text, no request that leaves ``file://`` and no failed load.

The pages are skipped when the book has not been built, except under ``CI=true`` where a
missing build fails. A synthetic broken page checks that the checks catch what they claim to.
"""

from __future__ import annotations

import json
import os
import re
import select
import shutil
import subprocess
import tempfile
import time
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
HTML = ROOT / "book" / "_build" / "html"
NOTEBOOKS = ROOT / "notebooks"
IN_CI = os.environ.get("CI") == "true"
PAGES = sorted(p for p in HTML.rglob("*.html") if p.relative_to(HTML).parts[0] not in {"_static", "_sources"})


def _require(condition: bool, message: str) -> None:
    """Skip when ``condition`` is false, or fail under CI=true."""
    if not condition:
        if IN_CI:
            pytest.fail(f"{message} (CI=true: this is a failure, not a skip)")
        pytest.skip(message)


def require_build() -> None:
    _require((HTML / "index.html").is_file(), f"book not built ({HTML} missing): run .ci/build_book.sh")


def chromium_executable() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


# -- static checks ---------------------------------------------------------------------
LOADING_ATTRS = {
    ("script", "src"),
    ("img", "src"),
    ("iframe", "src"),
    ("source", "src"),
    ("video", "src"),
    ("audio", "src"),
    ("embed", "src"),
    ("object", "data"),
}
SKIP_SCHEMES = {"mailto", "data", "javascript", "tel", "about", "blob"}


class _Refs(HTMLParser):
    """Collect ids and the (tag, attribute, url) references of one page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.refs: list[tuple[str, str, str, str]] = []  # tag, attribute, url, rel
        self.redirect = False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "meta" and (a.get("http-equiv") or "").lower() == "refresh":
            match = re.search(r"url\s*=\s*['\"]?([^'\"]+)", a.get("content") or "", re.IGNORECASE)
            if match:
                self.redirect = True
                self.refs.append((tag, "content", match.group(1).strip(), ""))
        for key in ("id",) + (("name",) if tag == "a" else ()):
            if a.get(key):
                self.ids.add(a[key])
        for attr in ("href", "src", "data"):
            if a.get(attr) is not None:
                self.refs.append((tag, attr, a[attr], (a.get("rel") or "").lower()))


def _parse(path: Path, cache: dict) -> _Refs:
    if path not in cache:
        parser = _Refs()
        parser.feed(path.read_text(encoding="utf-8", errors="replace"))
        cache[path] = parser
    return cache[path]


def link_problems(page: Path, cache: dict | None = None) -> list[str]:
    """Broken internal references and external resource loads of one HTML page."""
    cache = {} if cache is None else cache
    problems = []
    for tag, attr, url, rel in _parse(page, cache).refs:
        parts = urlsplit(url)
        if parts.scheme in SKIP_SCHEMES:
            continue
        loads = (tag, attr) in LOADING_ATTRS or (
            tag == "link" and rel not in {"", "canonical", "next", "prev"}
        )
        if parts.scheme or url.startswith("//"):
            if loads:
                problems.append(f"<{tag} {attr}={url!r}> loads a resource from the network")
            continue
        target = page if not parts.path else (page.parent / unquote(parts.path)).resolve()
        if target.is_dir():
            target = target / "index.html"
        if not target.is_file():
            problems.append(f"<{tag} {attr}={url!r}>: {target} does not exist")
            continue
        if (
            parts.fragment
            and target.suffix == ".html"
            and unquote(parts.fragment) not in _parse(target, cache).ids
        ):
            problems.append(f"<{tag} {attr}={url!r}>: no id {parts.fragment!r} in {target.name}")
    return problems


# -- Chromium through the DevTools protocol over a pipe --------------------------------
class Chromium:
    """Headless Chromium driven by the DevTools protocol on ``--remote-debugging-pipe``.

    The browser reads commands on fd 3 and writes replies on fd 4, NUL-terminated JSON; a
    shell maps them to this process's pipes. Every request to another host is refused (DNS
    mapped to nothing, ``http(s)``/``ws(s)`` URLs blocked), so nothing leaves the machine.
    """

    FLAGS = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--no-default-browser-check",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-extensions",
        "--mute-audio",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        "--remote-debugging-pipe",
        "--window-size=1280,1024",
    ]

    def __init__(self, executable: str, timeout: float = 60.0):
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="segplan-chromium-")
        self.log = open(Path(self.profile) / "stderr.log", "wb")  # noqa: SIM115 (closed in close())
        args = [executable, *self.FLAGS, f"--user-data-dir={self.profile}", "about:blank"]
        self.proc = subprocess.Popen(
            ["sh", "-c", 'exec "$0" "$@" 3<&0 4>&1 0</dev/null 1>/dev/null', *args],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.log,
        )
        self._buffer = b""
        self._id = 0
        self.events: list[dict] = []
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Network", "Runtime", "Log"):
            self.call(f"{domain}.enable", session=self.session)
        patterns = ["http://*", "https://*", "ws://*", "wss://*", "ftp://*"]
        self.call("Network.setBlockedURLs", {"urls": patterns}, session=self.session)

    def _read(self, deadline: float) -> dict:
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("Chromium did not answer in time")
            ready, _, _ = select.select([self.proc.stdout], [], [], left)
            if ready:
                chunk = os.read(self.proc.stdout.fileno(), 1 << 16)
                if not chunk:
                    raise RuntimeError(f"Chromium exited (code {self.proc.poll()}); see {self.log.name}")
                self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method: str, params: dict | None = None, session: str | None = None) -> dict:
        self._id += 1
        message = {"id": self._id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        self.proc.stdin.write(json.dumps(message).encode() + b"\0")
        self.proc.stdin.flush()
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._read(deadline)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_for(self, method: str, timeout: float) -> dict:
        deadline = time.monotonic() + timeout
        seen = 0
        while True:
            for event in self.events[seen:]:
                if event.get("method") == method:
                    return event
            seen = len(self.events)
            self.events.append(self._read(deadline))

    def settle(self, quiet: float = 0.3, timeout: float = 10.0) -> None:
        """Read events until no request is pending and the browser is quiet for ``quiet`` s."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            pending = set()
            for e in self.events:
                rid = e.get("params", {}).get("requestId")
                if e.get("method") == "Network.requestWillBeSent":
                    pending.add(rid)
                elif e.get("method") in ("Network.loadingFinished", "Network.loadingFailed"):
                    pending.discard(rid)
            try:
                self.events.append(self._read(min(deadline, time.monotonic() + quiet)))
            except TimeoutError:
                if not pending:
                    return

    def close(self) -> None:
        try:
            self.call("Browser.close")
        except (RuntimeError, TimeoutError, OSError):
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        self.log.close()
        shutil.rmtree(self.profile, ignore_errors=True)


# Runs in the page after its load event: waits for MathJax's first typesetting and for every
# image, then reports what a reader would see broken.
PAGE_REPORT_JS = r"""
(async () => {
  const later = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  const mj = window.MathJax;
  const mathjax = !!(mj && mj.startup && mj.startup.promise);
  if (mathjax) { await Promise.race([mj.startup.promise, later(30000)]); }
  const images = await Promise.all([...document.images].map(async (img) => {
    img.loading = "eager";
    try { await Promise.race([img.decode(), later(10000)]); } catch (e) {}
    return {src: img.getAttribute("src"), ok: img.complete && img.naturalWidth > 0};
  }));
  const math = [...document.querySelectorAll(".math")];
  const skip = "PRE, CODE, SCRIPT, STYLE, TEXTAREA, MJX-CONTAINER, MJX-ASSISTIVE-MML";
  const walker = document.createTreeWalker(document.body || document.documentElement, NodeFilter.SHOW_TEXT);
  const raw = [];
  const tex = /\$\$|\\\(|\\\)|\\\[|\\\]|\\begin\{|\$[^$\n]*[\\^_][^$\n]*\$/;
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    if (node.parentElement && node.parentElement.closest(skip)) continue;
    const m = node.textContent.match(tex);
    if (m) raw.push(node.textContent.trim().slice(0, 80));
  }
  return {
    mathjax_loaded: mathjax,
    broken_images: images.filter((i) => !i.ok).map((i) => i.src),
    images: images.length,
    outputs: document.querySelectorAll(".cell_output").length,
    math: math.length,
    unrendered_math: math.filter((e) => !e.querySelector("mjx-container"))
                         .map((e) => e.textContent.slice(0, 80)),
    math_errors: [...document.querySelectorAll("mjx-merror")].map((e) => e.textContent.slice(0, 80)),
    raw_tex: raw,
  };
})()
"""

LOCAL_SCHEMES = ("file:", "data:", "blob:", "about:")


def browser_problems(browser: Chromium, page: Path) -> tuple[list[str], dict]:
    """Open ``page`` and list what is broken: images, math, network requests, script errors."""
    browser.events.clear()
    result = browser.call("Page.navigate", {"url": page.as_uri()}, session=browser.session)
    if result.get("errorText"):
        return [f"navigation failed: {result['errorText']}"], {}
    browser.wait_for("Page.loadEventFired", timeout=60)
    evaluated = browser.call(
        "Runtime.evaluate",
        {"expression": PAGE_REPORT_JS, "awaitPromise": True, "returnByValue": True},
        session=browser.session,
    )
    if "exceptionDetails" in evaluated:
        return [f"page check script failed: {evaluated['exceptionDetails']}"], {}
    report = evaluated["result"]["value"]
    browser.settle()
    problems = [f"broken image {src!r}" for src in report["broken_images"]]
    problems += [f"math not rendered: {text!r}" for text in report["unrendered_math"]]
    problems += [f"MathJax error: {text!r}" for text in report["math_errors"]]
    problems += [f"raw TeX in the text: {text!r}" for text in report["raw_tex"]]
    if report["math"] and not report["mathjax_loaded"]:
        problems.append("the page has math but MathJax did not load")
    urls = {}
    for event in browser.events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Network.requestWillBeSent":
            url = params["request"]["url"]
            urls[params["requestId"]] = url
            if not url.startswith(LOCAL_SCHEMES):
                problems.append(f"request to the network: {url}")
        elif method == "Network.loadingFailed" and not params.get("canceled"):
            url = urls.get(params["requestId"], "?")
            if url.startswith(LOCAL_SCHEMES):  # network requests are reported above
                problems.append(f"failed to load {url}: {params.get('errorText')}")
        elif method == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            problems.append(
                f"script error: {details.get('exception', {}).get('description') or details['text']}"
            )
    return problems, report


# Pages that only redirect (index.html -> intro.html) are checked by the link test alone.
BROWSER_PAGES = [p for p in PAGES if not _parse(p, {}).redirect]


@pytest.fixture(scope="module")
def browser():
    executable = chromium_executable()
    _require(executable is not None, "Debian's chromium is not installed (.ci/setup.sh installs it)")
    instance = Chromium(executable)
    yield instance
    instance.close()


# -- the tests -------------------------------------------------------------------------
def test_book_is_built():
    require_build()
    assert PAGES, "no HTML pages in the build"


def test_every_notebook_is_a_chapter():
    require_build()
    missing = [
        nb.name
        for nb in sorted(NOTEBOOKS.glob("*.ipynb"))
        if not (HTML / "notebooks" / f"{nb.stem}.html").is_file()
    ]
    assert not missing, f"notebooks without a page in the book (add them to book/_toc.yml): {missing}"


def test_internal_links_and_no_external_resources():
    require_build()
    cache: dict = {}
    problems = {str(p.relative_to(HTML)): link_problems(p, cache) for p in PAGES}
    problems = {k: v for k, v in problems.items() if v}
    assert not problems, json.dumps(problems, indent=1)


@pytest.mark.parametrize(
    "page", BROWSER_PAGES or [None], ids=lambda p: str(p.relative_to(HTML)) if p else "no-build"
)
def test_page_in_chromium(browser, page):
    require_build()
    problems, report = browser_problems(browser, page)
    assert not problems, "\n".join(problems)
    if page.parent.name == "notebooks":
        assert report["outputs"] > 0, "a chapter without any cell output: was it executed?"


def test_chapters_have_claims_table():
    """The introduction shows the verdict table glued from every chapter (myst-nb glue)."""
    require_build()
    intro = (HTML / "intro.html").read_text(encoding="utf-8")
    tables = intro.count('class="dataframe"')
    chapters = len(list(NOTEBOOKS.glob("*.ipynb")))
    assert tables >= chapters, f"{tables} claims tables in intro.html for {chapters} notebooks"
    assert "reproduced" in intro


BROKEN_PAGE = r"""<!DOCTYPE html><html><head><meta charset="utf-8">
<script>window.MathJax = {};</script>
<script defer src="https://cdn.example.com/mathjax/tex-mml-chtml.js"></script>
</head><body><div id="top">
<p>A missing figure: <img src="missing.png" alt="x"></p>
<p><a href="nowhere.html">a missing page</a> and <a href="#no-such-anchor">a missing anchor</a>
and <a href="#top">a good anchor</a>.</p>
<p>Raw display math $$\int_0^1 f(x)\,dx$$ and inline $x^2$ left by the parser.</p>
<span class="math notranslate nohighlight">\(L^2 f''\)</span>
</div></body></html>
"""


def test_checks_catch_a_broken_page(tmp_path):
    """Each kind of breakage on a deliberately broken page is reported."""
    page = tmp_path / "broken.html"
    page.write_text(BROKEN_PAGE, encoding="utf-8")
    static = "\n".join(link_problems(page))
    assert "cdn.example.com" in static
    assert "missing.png" in static
    assert "nowhere.html" in static
    assert "no-such-anchor" in static
    assert "#top" not in static

    executable = chromium_executable()
    _require(executable is not None, "Debian's chromium is not installed (.ci/setup.sh installs it)")
    instance = Chromium(executable)
    try:
        problems, _ = browser_problems(instance, page)
    finally:
        instance.close()
    found = "\n".join(problems)
    assert "broken image 'missing.png'" in found
    assert "math not rendered" in found
    assert "raw TeX" in found and re.search(r"\$\$", found)
    assert "request to the network: https://cdn.example.com/mathjax/tex-mml-chtml.js" in found
