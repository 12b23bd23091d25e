"""What only the teacher edition may show of each exercise: distinctive text to search for.

Independent of the extension that builds the editions: read straight from the pages and the
solution scripts, so that a test built on it can catch the extension leaking.
"""

from __future__ import annotations

import html
import re
from pathlib import Path

DOCS = Path(__file__).resolve().parents[2] / "docs"
EXERCISES = DOCS / "exercises"
STEMS = sorted(p.stem for p in EXERCISES.glob("ex*.rst"))


def _public_code() -> set[str]:
    """Lines of the code every edition shows anyway: the package (its source pages) and the
    gallery's examples. A solution line that is also one of these gives nothing away."""
    files = [*(DOCS.parent / "ebantenna").rglob("*.py"), *(DOCS / "examples").glob("*.py")]
    return {line.strip() for f in files for line in f.read_text().splitlines()}


def solution_lines(stem: str) -> list[str]:
    """Lines of the worked solution a student must not see: code and comments at least 30
    characters long, outside the data block (which the statement shows), the imports and the
    package's and the gallery's own code."""
    source = (EXERCISES / "solutions" / f"{stem}.py").read_text()
    data = re.search(r"^# \[data\]\n(.*?)^# \[/data\]\n", source, flags=re.S | re.M)
    shown = {line.strip() for line in data.group(1).splitlines()} if data else set()
    if data:
        source = source.replace(data.group(0), "")
    source = source.split('"""', 2)[-1]  # the module docstring is the title, shown anyway
    page = (EXERCISES / f"{stem}.rst").read_text()
    statement = page[: page.index(".. teacher::")]
    lines, public = [], _public_code()
    for line in source.splitlines():
        line = line.strip()
        if (len(line) >= 30 and not line.startswith(("import ", "from ")) and line not in statement
                and line not in shown and line not in public):
            lines.append(line)
    return lines


def answer_pairs(stem: str) -> list[str]:
    """The ``name = value`` pairs of the teacher's "Expected answers" block, as text."""
    page = (EXERCISES / f"{stem}.rst").read_text()
    block = page[page.index(".. teacher:: answers\n") : page.index(".. teacher:: solution\n")]
    return [f"{n} = {v}" for n, v in re.findall(r"``(\w+) = ([-+0-9.eE]+)``", block)]


def visible_text(page_html: str) -> str:
    """The text of an HTML page, tags removed and entities decoded (code spans included)."""
    text = re.sub(r"<[^>]+>", "", page_html)
    return html.unescape(text)
