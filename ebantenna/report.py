"""Report writing shared by ``ebantenna reproduce`` and ``ebantenna bench``.

A report is a list of blocks (headings, paragraphs, tables, figures, preformatted text); one list
feeds both renderers, Markdown and standalone HTML, so the two files can never disagree.
:class:`FigureSet` saves matplotlib figures beside the report as PNG and remembers their paths;
:func:`text_table` formats rows of dicts as a fixed-width text table for a terminal.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Report", "FigureSet", "text_table"]


@dataclass
class Report:
    """An ordered list of report blocks.

    Examples
    --------
    >>> from ebantenna.report import Report
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


class FigureSet:
    """Saves matplotlib figures as PNG into one directory and remembers them by name.

    Parameters
    ----------
    out_dir : path
        Directory the PNG files go to (must exist).
    dpi : int
        Resolution of the saved files, dots per inch.

    Attributes
    ----------
    paths : dict of str to Path
        Every figure saved so far, by name, in order.

    Examples
    --------
    >>> import tempfile
    >>> from matplotlib.figure import Figure
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     figures = FigureSet(tmp)
    ...     fig = Figure()
    ...     _ = fig.subplots().plot([0, 1], [1, 0])
    ...     figures.save(fig, "line"), list(figures.paths)
    ('line.png', ['line'])
    """

    def __init__(self, out_dir, dpi: int = 120):
        self.out_dir = Path(out_dir)
        self.dpi = dpi
        self.paths: dict[str, Path] = {}

    def save(self, fig, name: str) -> str:
        """Save ``fig`` as ``name.png``, close it, and return the file name (relative)."""
        import matplotlib.pyplot as plt

        if not name or "/" in name:
            raise ValueError(f"name must be a plain file stem, got {name!r}")
        path = self.out_dir / f"{name}.png"
        fig.savefig(path, dpi=self.dpi, bbox_inches="tight")
        plt.close(fig)
        self.paths[name] = path
        return path.name


def text_table(columns, rows) -> str:
    """Rows of dicts as a fixed-width text table.

    Parameters
    ----------
    columns : sequence of (key, header, format)
        Which value of each row goes in a column, the column's header and a format
        specification for :func:`format` (for example ``"9.3f"``); the header is right-aligned
        to the width the format gives, or left-aligned when the format starts with ``<``.
    rows : sequence of dict
        One dict per row.

    Returns
    -------
    str
        Header line and one line per row, columns separated by one space.

    Examples
    --------
    >>> print(text_table([("name", "name", "<6"), ("t", "time s", "8.3f")],
    ...                  [{"name": "a", "t": 0.5}, {"name": "bb", "t": 12.25}]))
    name     time s
    a         0.500
    bb       12.250
    """
    columns = [tuple(c) for c in columns]
    for c in columns:
        if len(c) != 3:
            raise ValueError(f"columns must hold (key, header, format) triples, got {c!r}")
    cells = [[format(row[key], fmt) for key, _, fmt in columns] for row in rows]
    widths = [
        max([len(header)] + [len(r[i]) for r in cells])
        for i, (_, header, _) in enumerate(columns)
    ]
    def line(values):
        out = []
        for (_, _, fmt), width, v in zip(columns, widths, values, strict=True):
            out.append(v.ljust(width) if fmt.startswith("<") else v.rjust(width))
        return " ".join(out).rstrip()

    return "\n".join([line([h for _, h, _ in columns]), *(line(r) for r in cells)])
