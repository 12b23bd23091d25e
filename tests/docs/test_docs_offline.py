"""The built documentation works offline: every script and style is local, and the formulas typeset.

A classroom without internet, or the rig's Raspberry Pi, must see the formulas typeset, not raw
LaTeX. The pages are opened in headless Chromium with every network request made to fail (an
unreachable proxy and a resolver that finds no host); only ``file://`` loads succeed. These tests
need both built editions (``python -m sphinx -b html docs docs/_build/html`` and, for the teacher
edition, ``python -m sphinx -t teacher -b html docs docs/_build/teacher``) and, for the browser
tests, Debian's ``chromium``; ``.ci/run`` provides them, so they are never skipped there.
"""

from __future__ import annotations

import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import pytest
from unloaded_time import run

DOCS = Path(__file__).resolve().parents[2] / "docs"
#: the student edition (the default build) and the teacher edition (``-t teacher``)
BUILDS = {"student": DOCS / "_build" / "html", "teacher": DOCS / "_build" / "teacher"}
#: pages with display and inline math: sympy's derived matrices, the SVM dual, the signal chain
MATH_PAGES = ["theory/element.html", "theory/filters.html", "theory/kalman.html"]



def _built(edition: str):
    """The parameter of one edition's build directory, skipped with a reason when not built."""
    build = BUILDS[edition]
    flag = "" if edition == "student" else "-t teacher "
    mark = pytest.mark.skipif(
        not (build / "index.html").is_file(),
        reason=f"{edition} edition not built (python -m sphinx {flag}-b html docs {build})",
    )
    return pytest.param(build, id=edition, marks=mark)


#: every test on built pages runs on both editions
each_build = pytest.mark.parametrize("build", [_built(e) for e in sorted(BUILDS)])
CHROMIUM = next(
    (p for p in map(shutil.which, ("chromium", "chromium-browser", "google-chrome")) if p), None
)
needs_chromium = pytest.mark.skipif(
    CHROMIUM is None, reason="no Chromium on this machine (Debian: apt-get install chromium)"
)


class _Page(HTMLParser):
    """Collects the external resources a page loads and the text a reader sees."""

    #: elements whose text is not shown as prose: code, scripts, and MathJax's hidden MathML copy
    HIDDEN = {"script", "style", "pre", "code", "textarea", "mjx-assistive-mml", "template"}

    def __init__(self):
        super().__init__()
        self.resources: list[str] = []
        self.math_containers = 0
        self.visible: list[str] = []
        self._hidden_depth = 0

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "script" and attrs.get("src"):
            self.resources.append(attrs["src"])
        if tag == "link" and "stylesheet" in (attrs.get("rel") or "") and attrs.get("href"):
            self.resources.append(attrs["href"])
        if tag in ("img", "iframe") and attrs.get("src"):
            self.resources.append(attrs["src"])
        if tag == "mjx-container":
            self.math_containers += 1
        if tag in self.HIDDEN:
            self._hidden_depth += 1

    def handle_endtag(self, tag):
        if tag in self.HIDDEN and self._hidden_depth:
            self._hidden_depth -= 1

    def handle_data(self, data):
        if not self._hidden_depth:
            self.visible.append(data)


def _parse(html: str) -> _Page:
    page = _Page()
    page.feed(html)
    return page


def _is_remote(url: str) -> bool:
    return bool(re.match(r"^([a-z][a-z0-9+.-]*:)?//", url, flags=re.I)) and not url.startswith(
        "file:"
    )


def _render(path: Path, tmp_path: Path) -> str:
    """The DOM of ``path`` after Chromium ran its scripts, with the network made to fail."""
    profile = tmp_path / f"profile-{path.stem}"
    profile.mkdir()
    command = [
        CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
        "--no-first-run", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", f"--user-data-dir={profile}",
        # no network: every request goes to a closed port, and no host name resolves
        "--proxy-server=http://127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        # run the page's scripts (MathJax typesets on load) before the DOM is printed
        "--virtual-time-budget=15000", "--dump-dom", path.as_uri(),
    ]  # fmt: skip
    # the page's scripts run on a virtual clock (15 s budget, no waiting); the browser's own
    # time (waits for a CPU left out; its renderer's slowness still counts) past 120 s is a hang
    done = run(command, 120, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


@each_build
def test_every_built_page_loads_only_local_scripts_and_styles(build):
    pages = sorted(build.rglob("*.html"))
    assert len(pages) > 50  # the whole site, not a stray file
    remote = {}
    for page in pages:
        found = [u for u in _parse(page.read_text(encoding="utf-8")).resources if _is_remote(u)]
        if found:
            remote[str(page.relative_to(build))] = found
    for css in build.rglob("*.css"):
        found = re.findall(r"url\(\s*['\"]?((?:[a-z]+:)?//[^)'\"]+)", css.read_text("utf-8"))
        if found:
            remote[str(css.relative_to(build))] = found
    assert not remote, f"pages that load from the network: {remote}"


@each_build
def test_mathjax_ships_with_its_fonts(build):
    mathjax = build / "_static" / "mathjax"
    assert (mathjax / "tex-chtml.js").is_file()
    assert list((mathjax / "output" / "chtml" / "fonts" / "woff-v2").glob("MathJax_Main-*.woff"))
    html = (build / MATH_PAGES[0]).read_text(encoding="utf-8")
    assert "_static/mathjax/tex-chtml.js" in html


@needs_chromium
def test_the_browser_really_is_offline(tmp_path):
    # The witness that the set-up cuts the network: MathJax from its CDN does not typeset here.
    page = tmp_path / "cdn.html"
    page.write_text(
        "<html><head><script defer "
        'src="https://cdn.jsdelivr.net/npm/mathjax@3/es5/tex-chtml.js"></script></head>'
        r"<body><p>\(\frac{1}{2}\)</p></body></html>"
    )
    rendered = _parse(_render(page, tmp_path))
    assert rendered.math_containers == 0
    assert r"\frac" in "".join(rendered.visible)


@each_build
@needs_chromium
@pytest.mark.parametrize("name", MATH_PAGES)
def test_math_is_typeset_offline(build, name, tmp_path):
    source = (build / name).read_text(encoding="utf-8")
    assert r"\frac" in source  # the page has fractions to typeset
    n_math = source.count('class="math notranslate')  # Sphinx's span or div of each formula
    rendered = _parse(_render(build / name, tmp_path))
    assert rendered.math_containers >= n_math > 0
    visible = "".join(rendered.visible)
    assert r"\frac" not in visible and r"\(" not in visible and r"\[" not in visible
