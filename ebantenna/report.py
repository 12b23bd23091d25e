"""Report writing shared by ``ebantenna reproduce`` and ``ebantenna bench``.

A report is a list of blocks (headings, paragraphs, tables, figures, preformatted text); one list
feeds both renderers, Markdown and standalone HTML, so the two files can never disagree.
:class:`FigureSet` saves matplotlib figures beside the report as PNG and remembers their paths;
:func:`text_table` formats rows of dicts as a fixed-width text table for a terminal.
"""

from __future__ import annotations

import html
import os
from dataclasses import dataclass, field
from pathlib import Path

from ._validate import check_int, describe

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

    def __post_init__(self):
        _text("title", self.title)
        if not isinstance(self.blocks, list):
            raise TypeError(f"blocks must be a list, got {type(self.blocks).__name__}")

    def heading(self, text: str) -> None:
        """A section heading."""
        self.blocks.append(("h2", _text("text", text)))

    def paragraph(self, text: str) -> None:
        """A paragraph of plain text."""
        self.blocks.append(("p", _text("text", text)))

    def table(self, headers, rows) -> None:
        """A table; cells are formatted with ``str`` (each row as long as ``headers``)."""
        if isinstance(headers, str | bytes) or not hasattr(headers, "__iter__"):
            raise TypeError(f"headers must be a sequence of column names, got "
                            f"{describe(headers)}")
        headers = [str(h) for h in headers]
        if isinstance(rows, str | bytes) or not hasattr(rows, "__iter__"):
            raise TypeError(f"rows must be a sequence of rows, got {describe(rows)}")
        cells = []
        for i, row in enumerate(rows):
            if isinstance(row, str | bytes) or not hasattr(row, "__iter__"):
                raise TypeError(f"rows[{i}] must be a sequence of cells, got {describe(row)}")
            cells.append([str(c) for c in row])
            if len(cells[-1]) != len(headers):
                raise ValueError(f"rows[{i}] has {len(cells[-1])} cells for {len(headers)} "
                                 "headers")
        self.blocks.append(("table", headers, cells))

    def figure(self, path: str, caption: str) -> None:
        """A figure, given by its path relative to the report."""
        if not isinstance(path, str | os.PathLike) or not str(path):
            raise TypeError(f"path must be a file name or path, got {describe(path)}")
        self.blocks.append(("img", str(path), _text("caption", caption)))

    def preformatted(self, text: str) -> None:
        """Fixed-width text (confusion matrices, logs)."""
        self.blocks.append(("pre", _text("text", text)))

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
        from ._validate import check_path

        directory = Path(check_path("directory", directory))
        _stem("stem", stem)
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
        from ._validate import check_path

        self.out_dir = Path(check_path("out_dir", out_dir))
        self.dpi = check_int("dpi", dpi, minimum=10, maximum=2400)
        self.paths: dict[str, Path] = {}

    def save(self, fig, name: str) -> str:
        """Save ``fig`` as ``name.png``, close it, and return the file name (relative)."""
        import matplotlib.pyplot as plt

        _stem("name", name)
        path = self.out_dir / f"{name}.png"
        fig.savefig(path, dpi=self.dpi, bbox_inches="tight")
        plt.close(fig)
        self.paths[name] = path
        return path.name


def _text(name: str, value) -> str:
    """``value`` if it is a string, else a TypeError naming ``name``."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {describe(value)} "
                        f"({type(value).__name__})")
    return value


def _stem(name: str, value) -> str:
    """``value`` if it is a plain file stem: a non-empty string naming no folder."""
    _text(name, value)
    if value in ("", ".", "..") or any(c in value for c in "/\\\0"):
        raise ValueError(f"{name} must be a plain file stem (no folder, not empty), got "
                         f"{value!r:.60}")
    return value


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
    rows = list(rows)
    for i, row in enumerate(rows):
        missing = [key for key, _, _ in columns if not isinstance(row, dict) or key not in row]
        if missing:
            raise ValueError(f"rows[{i}] must be a dict holding every column's key; missing "
                             f"{', '.join(map(repr, missing))}")
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
