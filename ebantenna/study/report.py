"""A tiny document model rendered twice: Markdown and standalone HTML.

The study's report is a list of blocks (headings, paragraphs, tables, figures, preformatted text);
one list feeds both renderers, so the two files can never disagree.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Report"]


@dataclass
class Report:
    """An ordered list of report blocks.

    Examples
    --------
    >>> from ebantenna.study.report import Report
    >>> r = Report("Title")
    >>> r.table(["a", "b"], [[1, 2.5]])
    >>> print(r.markdown().splitlines()[2:5])
    ['| a | b |', '| --- | --- |', '| 1 | 2.5 |']
    """

    title: str
    blocks: list = field(default_factory=list)

    def heading(self, text: str) -> None:
        """A section heading."""
        self.blocks.append(("h2", text))

    def paragraph(self, text: str) -> None:
        """A paragraph of plain text."""
        self.blocks.append(("p", text))

    def table(self, headers, rows) -> None:
        """A table; cells are formatted with ``str``."""
        self.blocks.append(
            ("table", [str(h) for h in headers], [[str(c) for c in r] for r in rows])
        )

    def figure(self, path: str, caption: str) -> None:
        """A figure, given by its path relative to the report."""
        self.blocks.append(("img", path, caption))

    def preformatted(self, text: str) -> None:
        """Fixed-width text (confusion matrices, logs)."""
        self.blocks.append(("pre", text))

    def markdown(self) -> str:
        """The report as GitHub-flavoured Markdown."""
        out = [f"# {self.title}", ""]
        for block in self.blocks:
            kind = block[0]
            if kind == "h2":
                out += [f"## {block[1]}", ""]
            elif kind == "p":
                out += [block[1], ""]
            elif kind == "table":
                headers, rows = block[1], block[2]
                out.append("| " + " | ".join(headers) + " |")
                out.append("| " + " | ".join("---" for _ in headers) + " |")
                out += ["| " + " | ".join(c.replace("|", "\\|") for c in r) + " |" for r in rows]
                out.append("")
            elif kind == "img":
                out += [f"![{block[2]}]({block[1]})", "", f"*{block[2]}*", ""]
            elif kind == "pre":
                out += ["```", block[1], "```", ""]
        return "\n".join(out)

    def html(self) -> str:
        """The report as one standalone HTML page."""
        e = html.escape
        body = [f"<h1>{e(self.title)}</h1>"]
        for block in self.blocks:
            kind = block[0]
            if kind == "h2":
                body.append(f"<h2>{e(block[1])}</h2>")
            elif kind == "p":
                body.append(f"<p>{e(block[1])}</p>")
            elif kind == "table":
                head = "".join(f"<th>{e(h)}</th>" for h in block[1])
                rows = "".join(
                    "<tr>" + "".join(f"<td>{e(c)}</td>" for c in r) + "</tr>" for r in block[2]
                )
                body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>")
            elif kind == "img":
                body.append(
                    f'<figure><img src="{e(block[1])}" alt="{e(block[2])}">'
                    f"<figcaption>{e(block[2])}</figcaption></figure>"
                )
            elif kind == "pre":
                body.append(f"<pre>{e(block[1])}</pre>")
        style = (
            "body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.45}"
            "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;"
            "padding:.25em .6em;text-align:right}th{background:#eee}img{max-width:100%}"
            "figcaption{font-style:italic;color:#444}pre{background:#f6f6f6;padding:.6em}"
        )
        return (
            "<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>{e(self.title)}</title><style>{style}</style></head><body>"
            + "\n".join(body)
            + "</body></html>\n"
        )

    def write(self, directory, stem: str = "report") -> tuple[Path, Path]:
        """Write ``stem.md`` and ``stem.html`` into ``directory``; returns both paths."""
        directory = Path(directory)
        md, page = directory / f"{stem}.md", directory / f"{stem}.html"
        md.write_text(self.markdown(), encoding="utf-8")
        page.write_text(self.html(), encoding="utf-8")
        return md, page
