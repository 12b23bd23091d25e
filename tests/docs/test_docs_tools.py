"""The build-time tools of the docs: sympy rendering, errata table, CLI help, inventories."""

import ast
import importlib
import inspect
import io
import re
import runpy
import zlib
from pathlib import Path

import ebantenna_docs
import make_inventories
import public_names
import pytest
import sympy as sp
from sphinx.util.inventory import InventoryFile

from ebantenna.fem import symbolic

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_render_latex_is_sympy_latex_of_the_package_result():
    K, _M = symbolic.element_matrices()
    names = {symbolic.rhoA: r"\rho A", symbolic.EI: "EI", symbolic.l1: "l_1", symbolic.l2: "l_2"}
    assert ebantenna_docs.render_latex("element_matrices()[0]") == sp.latex(K, symbol_names=names)
    assert ebantenna_docs.render_latex("element_matrices()[0]", "K =").startswith("K = ")


def test_factored_rendering_keeps_the_matrix():
    latex = ebantenna_docs.render_latex("element_matrices()[1]", factor="rhoA * l / 420")
    assert latex.startswith(r"\frac{l \rho A}{420}")
    for entry in ("156", "22 l", "54", "- 13 l", "- 3 l^{2}"):
        assert entry in latex
    # the factor taken out is exact: the inner matrix times the factor is M again
    factor = symbolic.rhoA * symbolic.l / 420
    inner = (symbolic.element_matrices()[1] / factor).applyfunc(sp.factor)
    assert inner[0, 0] == 156 and inner[0, 1] == 22 * symbolic.l


def test_broken_expression_raises():
    with pytest.raises(NameError):
        ebantenna_docs.render_latex("no_such_function()")


def test_errata_rows_follow_paper_errata():
    rows = ebantenna_docs.errata_rows()
    errata = symbolic.paper_errata()
    assert len(rows) == len(errata) > 0
    for row, e in zip(rows, errata, strict=True):
        assert row[:3] == [e.matrix, str(e.row), str(e.col)] and row[5] == e.reason
    # the typo in the printed element stiffness, K(3, 4) = +6 EI / l^2 instead of -6 EI / l^2
    assert ["K", "3", "4", r"\frac{6 EI}{l^{2}}", r"- \frac{6 EI}{l^{2}}", "typo", "sign"] in rows


def test_erratum_kinds():
    errata = symbolic.paper_errata()
    kinds = {(e.matrix, e.row, e.col): ebantenna_docs.erratum_kind(e) for e in errata}
    # M1(6, 3) and M1(6, 4) belong to element 2 alone but are printed with l1 where l2 belongs
    assert kinds[("M1", 6, 3)] == kinds[("M1", 6, 4)] == "subscript"
    assert kinds[("K", 3, 4)] == kinds[("K1", 5, 4)] == "sign"
    assert kinds[("K1", 3, 3)] == "common factor"
    # a made-up erratum of each kind is told apart from the others
    made = symbolic.Erratum("M1", 6, 3, "-13*l*l1*rhoA/420", "-13*l2**2*rhoA/420", "typo")
    assert ebantenna_docs.erratum_kind(made) == "subscript"
    made = symbolic.Erratum("M1", 6, 3, "-12*l*l2*rhoA/420", "-13*l2**2*rhoA/420", "typo")
    assert ebantenna_docs.erratum_kind(made) == "wrong term"


def test_cli_help_is_the_programs_own():
    from ebantenna.cli import build_parser

    text = ebantenna_docs.cli_help()
    sub = next(a for a in build_parser()._actions if isinstance(getattr(a, "choices", None), dict))
    for command in sub.choices:
        assert command in text
        assert ebantenna_docs.cli_help(command).startswith(f"usage: ebantenna {command}")
    with pytest.raises(KeyError, match="no command"):
        ebantenna_docs.cli_help("no-such-command")


def test_user_guide_documents_only_existing_commands():
    from ebantenna.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(getattr(a, "choices", None), dict))
    text = (DOCS / "user_guide" / "cli.rst").read_text()
    import re

    for command in re.findall(r"\.\. ebantenna-cli:: (\S+)", text):
        assert command in sub.choices
    for command in re.findall(r"^   ebantenna (\w+)", text, flags=re.M):
        assert command in sub.choices


@pytest.mark.parametrize("key", sorted(make_inventories.INVENTORIES))
def test_committed_inventory_is_valid_and_up_to_date(key, tmp_path):
    project, _dist, base, entries = make_inventories.INVENTORIES[key]
    committed = (DOCS / "_inventories" / f"{key}.inv").read_bytes()
    # Sphinx itself can read it, and finds every entry at its URL under the project's base.
    inventory = InventoryFile.load(io.BytesIO(committed), base, lambda b, u: b + u)
    items = {}
    for role_items in (inventory.data if hasattr(inventory, "data") else inventory).values():
        items.update(role_items)
    assert set(items) == {name for name, _role, _uri in entries}
    for name, _role, uri in entries:
        item = items[name]
        url = item.uri if hasattr(item, "uri") else item[2]
        assert url == base + uri.replace("$", name) and url.startswith("https://")
    # the header names the project; regenerating gives the same bytes
    header, _, body = committed.partition(b"zlib.\n")
    assert f"# Project: {project}".encode() in header
    assert zlib.decompress(body).decode().count("\n") == len(entries)
    # Regenerating gives the same bytes, but for the "# Version:" line, which records the version
    # installed where the files were made (older Pythons get older releases).
    make_inventories.write_inventories(tmp_path)

    def without_version(data):
        return b"\n".join(x for x in data.split(b"\n") if not x.startswith(b"# Version:"))

    assert without_version((tmp_path / f"{key}.inv").read_bytes()) == without_version(committed)


def test_inventory_refuses_objects_that_do_not_exist():
    assert make_inventories.resolve("numpy.linalg.eigh") is not None
    with pytest.raises(LookupError):
        make_inventories.resolve("numpy.linalg.no_such_function")


def test_intersphinx_mapping_points_at_local_files():
    mapping = make_inventories.intersphinx_mapping("_inventories")
    # Python (numpydoc links every "float" and "dict" of a docstring to it) and every library the
    # docs link to
    libraries = {"numpy", "scipy", "sklearn", "sympy", "matplotlib", "joblib", "smbus2"}
    assert set(mapping) == {"python"} | libraries
    for url, path in mapping.values():
        assert url.startswith("https://") and (DOCS / path).is_file()


@pytest.mark.parametrize("key", sorted(make_inventories.INVENTORIES))
def test_every_inventory_name_imports(key):
    for name, role, _uri in make_inventories.INVENTORIES[key][3]:
        obj = make_inventories.resolve(name)
        if role == "module":
            assert inspect.ismodule(obj), name
        elif role == "class":
            assert isinstance(obj, type), name


def test_builtin_names_resolve_to_the_builtins():
    assert make_inventories.resolve("float") is float
    assert make_inventories.resolve("None") is None
    with pytest.raises(LookupError):
        make_inventories.resolve("no_such_builtin")


@pytest.fixture(scope="module")
def conf():
    from sphinx.util.tags import Tags

    # Sphinx runs conf.py with the build's tags (-t teacher) as the global ``tags``
    return runpy.run_path(str(DOCS / "conf.py"), init_globals={"tags": Tags()})


def test_conf_reports_every_dead_reference(conf):
    # with nitpicky on, the -W build of CI fails on any reference that has no target
    assert conf["nitpicky"] is True
    assert "public_names" in conf["extensions"]
    assert "nitpick_ignore_regex" not in conf  # no pattern that could hide real dead links


def test_nitpick_ignore_holds_only_existing_private_objects(conf):
    # bare names, as numpydoc writes them from a docstring's type, and where they are defined
    homes = {"AnalysedPart": "ebantenna.signal._guards.AnalysedPart"}
    for _role, target in conf["nitpick_ignore"]:
        full = homes.get(target, target)
        # the object exists (a typo would hide nothing), and it lives in a private module, which
        # the API pages do not document
        make_inventories.resolve(full)
        assert any(part.startswith("_") for part in full.split(".")), target


def test_numpydoc_aliases_point_at_real_objects(conf):
    inventory_names = {
        name for entries in make_inventories.INVENTORIES.values() for name, _r, _u in entries[3]
    }
    for word, target in conf["numpydoc_xref_aliases"].items():
        if target.startswith("ebantenna."):
            make_inventories.resolve(target)
        else:
            assert target in inventory_names, (word, target)
    # a word is either linked or ignored, not both
    assert not set(conf["numpydoc_xref_aliases"]) & conf["numpydoc_xref_ignore"]


def test_public_names_finds_the_object_itself():
    from ebantenna.signal import decay, fit_decay
    from ebantenna.signal.kalman import KalmanFilter

    documented = {"ebantenna.signal.decay.fit_decay", "ebantenna.signal.decay.envelope"}
    assert public_names.documented_name(decay.envelope, "envelope", documented) == (
        "ebantenna.signal.decay.envelope"
    )
    assert public_names.import_name("ebantenna.signal.fit_decay") is fit_decay is decay.fit_decay
    assert public_names.documented_name(fit_decay, "fit_decay", documented) == (
        "ebantenna.signal.decay.fit_decay"
    )
    # a name that is not documented, or another object of the same name, is not linked
    elsewhere = {"ebantenna.other.fit_decay"}
    assert public_names.documented_name(fit_decay, "fit_decay", elsewhere) is None
    other = {"ebantenna.signal.spectral.dominant_frequency"}
    assert public_names.documented_name(fit_decay, "dominant_frequency", other) is None
    assert public_names.import_name("ebantenna.signal.no_such_name") is public_names._MISSING
    # a classmethod is bound anew on every access: the same method, not the same object
    assert KalmanFilter.random_walk is not KalmanFilter.random_walk
    assert public_names.same(KalmanFilter.random_walk, KalmanFilter.random_walk)
    assert not public_names.same(KalmanFilter.random_walk, KalmanFilter.resonator)


def test_public_names_reads_bare_names_in_their_module():
    assert public_names.candidates("ebantenna.ml.SVC", "ebantenna.signal", None) == [
        "ebantenna.ml.SVC"
    ]
    assert public_names.candidates("fit", "ebantenna.ml.svc", "SVC") == [
        "ebantenna.ml.svc.SVC.fit", "ebantenna.ml.svc.fit"
    ]
    assert public_names.candidates("float", None, None) == []


def test_autosummary_takes_a_module_before_a_function_of_the_same_name():
    import ebantenna.study

    module = importlib.import_module("ebantenna.study.reproduce")

    # ebantenna.study re-exports the function reproduce of its module reproduce
    assert ebantenna.study.reproduce is not module
    importer = public_names.module_first(lambda name, grouped=True: ("fallback", None, name))
    assert importer("ebantenna.study.reproduce")[0] is module
    assert importer("ebantenna.study.reproduce.StudyResult")[0] == "fallback"


def test_exercise_links_do_not_repeat_the_word_exercise():
    # an exercise page's title starts with "Exercise N:", so "exercise :doc:`...`" rendered as
    # "exercise Exercise N: ..."; a link says "exercise N" through its own title instead
    pattern = re.compile(r"\b[Ee]xercises?\s+:doc:`[^`<]*`")
    pages = [p for p in DOCS.rglob("*.rst") if not {"_build", "auto_examples"} & set(p.parts)]
    pages += list((DOCS / "examples").glob("*.py"))
    pages += list((DOCS.parent / "ebantenna").rglob("*.py"))
    found = [f"{p.name}: {m.group(0)!r}" for p in pages for m in pattern.finditer(p.read_text())]
    assert found == []


def test_gallery_has_at_least_eight_titled_examples():
    examples = sorted((DOCS / "examples").glob("plot_*.py"))
    assert len(examples) >= 8
    for path in examples:
        doc = ast.get_docstring(ast.parse(path.read_text()))
        assert doc and doc.splitlines()[1].startswith("===="), path.name
