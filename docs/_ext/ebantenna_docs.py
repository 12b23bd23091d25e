"""Sphinx directives that render the package's own results into the documentation.

``.. sympy-math::``
    Evaluates a Python expression in the namespace of :mod:`ebantenna.fem.symbolic` (plus ``sp`` for
    sympy) and renders the result with :func:`sympy.latex` as a display equation, so that the theory
    pages show what the code derives instead of a retyped copy::

        .. sympy-math:: element_matrices()[0]
           :lhs: \\mathbf{K}_e =

``.. ebantenna-cli:: [COMMAND]``
    The ``--help`` text of the installed ``ebantenna`` command (or one subcommand), so that the user
    guide documents exactly the commands and options that exist.

``.. paper-errata::``
    The table of printed entries that differ from the derivation, from
    :func:`ebantenna.fem.symbolic.paper_errata`, and the notes of
    :data:`ebantenna.fem.symbolic.PAPER_NOTES` as a bullet list.

The functions that produce the LaTeX and the table rows are plain Python, so that the tests can
check them without building the site.
"""

from __future__ import annotations

import sympy as sp
from docutils import nodes
from docutils.parsers.rst import directives
from sphinx.directives.patches import MathDirective
from sphinx.util.docutils import SphinxDirective

__all__ = [
    "latex", "evaluate", "render_latex", "erratum_kind", "errata_rows", "cli_help", "setup",
]


def _symbol_names() -> dict:
    from ebantenna.fem import symbolic as s

    return {s.rhoA: r"\rho A", s.EI: "EI", s.l1: "l_1", s.l2: "l_2"}


def latex(value) -> str:
    """:func:`sympy.latex` with the package's symbols written as in the textbook (``rho A``)."""
    return sp.latex(value, symbol_names=_symbol_names())


def _namespace() -> dict:
    from ebantenna.fem import symbolic

    namespace = {name: getattr(symbolic, name) for name in symbolic.__all__}
    namespace["sp"] = sp
    return namespace


def evaluate(expression: str):
    """Value of ``expression`` in the namespace of :mod:`ebantenna.fem.symbolic` (and ``sp``)."""
    return eval(expression, _namespace())  # noqa: S307 - the docs' own source, not user input


def render_latex(expression: str, lhs: str = "", *, factor: str | None = None) -> str:
    """LaTeX of an evaluated sympy expression, optionally with a left-hand side.

    Parameters
    ----------
    expression : str
        A Python expression, e.g. ``"element_matrices()[0]"``.
    lhs : str
        LaTeX put before the result, e.g. ``"K ="``.
    factor : str, optional
        A Python expression for a scalar to take out of a matrix (``"EI/l**3"``): the result is
        printed as ``factor * (matrix / factor)``, each entry simplified.
    """
    value = evaluate(expression)
    if factor is None:
        body = latex(value)
    else:
        scalar = evaluate(factor)
        inner = (value / scalar).applyfunc(sp.factor)
        body = latex(scalar) + " " + latex(inner)
    return f"{lhs} {body}".strip()


def _locals() -> dict:
    from ebantenna.fem import symbolic as s

    return {"l": s.l, "l1": s.l1, "l2": s.l2, "EI": s.EI, "rhoA": s.rhoA}


def erratum_kind(erratum) -> str:
    """What is wrong with one printed entry, in finer words than its ``reason``.

    ``"common factor"`` as in :func:`~ebantenna.fem.symbolic.paper_errata`; a ``"typo"`` of an
    entry that belongs to one element (length ``l1`` or ``l2``, the printed ``l`` read as that
    length) is a ``"sign"`` when the printed entry is minus the derived one, a ``"subscript"`` when
    writing the element's own length for the other element's length in it gives the derived one,
    and a ``"wrong term"`` otherwise.
    """
    from ebantenna.fem.symbolic import l, l1, l2

    if erratum.reason != "typo":
        return erratum.reason
    printed = sp.sympify(erratum.printed, locals=_locals())
    derived = sp.sympify(erratum.derived, locals=_locals())
    lengths = derived.free_symbols & {l, l1, l2}
    own = next(iter(lengths)) if len(lengths) == 1 else None
    if own is not None:
        printed = printed.subs(l, own)
    if sp.simplify(printed + derived) == 0:
        return "sign"
    other = {l1: l2, l2: l1}.get(own)
    if other is not None and sp.simplify(printed.subs(other, own) - derived) == 0:
        return "subscript"
    return "wrong term"


def errata_rows() -> list[list[str]]:
    """Rows ``[matrix, row, col, printed, derived, reason, kind]`` of the errata table.

    The printed and derived cells are LaTeX; ``kind`` is :func:`erratum_kind`.
    """
    from ebantenna.fem.symbolic import paper_errata

    rows = []
    for e in paper_errata():
        rows.append(
            [
                e.matrix,
                str(e.row),
                str(e.col),
                latex(sp.sympify(e.printed, locals=_locals())),
                latex(sp.sympify(e.derived, locals=_locals())),
                e.reason,
                erratum_kind(e),
            ]
        )
    return rows


class SympyMath(MathDirective):
    """``.. sympy-math:: EXPRESSION``, options ``:lhs:``, ``:factor:`` and Sphinx's ``:label:``."""

    has_content = False
    required_arguments = 1
    optional_arguments = 0
    option_spec = {
        **MathDirective.option_spec,
        "lhs": directives.unchanged,
        "factor": directives.unchanged,
    }

    def run(self):
        expression = self.arguments[0]
        try:
            latex = render_latex(
                expression, self.options.get("lhs", ""), factor=self.options.get("factor")
            )
        except Exception as exc:  # a broken expression must fail the build, with its location
            raise self.error(f"sympy-math: cannot evaluate {expression!r}: {exc}") from exc
        self.arguments = [latex]
        # the grey box marked "derived" (docs/_static/ebantenna.css): the package's own result
        box = nodes.container(classes=["derived"])
        box.extend(super().run())
        return [box]


def _cell(text: str, math: bool = False):
    entry = nodes.entry()
    para = nodes.paragraph()
    para += nodes.math(text, text) if math else nodes.Text(text)
    entry += para
    return entry


class PaperErrata(SphinxDirective):
    """``.. paper-errata::``: the generated errata table and the paper's notes."""

    has_content = False

    def run(self):
        from ebantenna.fem.symbolic import PAPER_NOTES

        headers = ["matrix", "row", "col", "printed", "derived", "reason", "what is wrong"]
        table = nodes.table(classes=["errata"])
        group = nodes.tgroup(cols=len(headers))
        table += group
        for width in (8, 5, 5, 30, 30, 14, 14):
            group += nodes.colspec(colwidth=width)
        head = nodes.thead()
        row = nodes.row()
        for h in headers:
            row += _cell(h)
        head += row
        group += head
        body = nodes.tbody()
        for cells in errata_rows():
            row = nodes.row()
            for k, text in enumerate(cells):
                row += _cell(text, math=k in (3, 4))
            body += row
        group += body
        notes = nodes.bullet_list()
        for note in PAPER_NOTES:
            item = nodes.list_item()
            item += nodes.paragraph(text=note)
            notes += item
        return [table, notes]


def cli_help(command: str | None = None, width: int = 90) -> str:
    """The ``--help`` text of ``ebantenna`` (or of one command), as the program prints it."""
    import os

    from ebantenna.cli import build_parser

    previous = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(width)  # argparse wraps to the terminal width
    try:
        parser = build_parser()
        if command is not None:
            actions = [a for a in parser._actions if hasattr(a, "choices") and a.choices]
            sub = next(a for a in actions if isinstance(a.choices, dict))
            if command not in sub.choices:
                known = sorted(sub.choices)
                raise KeyError(f"ebantenna has no command {command!r}; it has {known}")
            parser = sub.choices[command]
        return parser.format_help()
    finally:
        if previous is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = previous


class EbantennaCli(SphinxDirective):
    """``.. ebantenna-cli:: [COMMAND]``: the installed command's help text, as a literal block."""

    optional_arguments = 1

    def run(self):
        command = self.arguments[0] if self.arguments else None
        try:
            text = cli_help(command)
        except KeyError as exc:
            raise self.error(str(exc)) from exc
        prompt = "$ ebantenna " + (f"{command} " if command else "") + "--help\n"
        block = nodes.literal_block(prompt + text, prompt + text, language="text")
        self.set_source_info(block)
        return [block]


def setup(app):
    app.add_directive("ebantenna-cli", EbantennaCli)
    app.add_directive("sympy-math", SympyMath)
    app.add_directive("paper-errata", PaperErrata)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
