"""Let a reference use the name a user imports: ``ebantenna.signal.fit_decay`` for the function the
API pages document as ``ebantenna.signal.decay.fit_decay``.

Each subpackage re-exports its main names (``from ebantenna.signal import fit_decay``), while the
API reference documents every object once, in the module that defines it. When Sphinx finds no
page for a Python reference, this extension imports the name, the way Python would read it:

- a dotted name starting with ``ebantenna`` as it is written;
- a bare name (``Scene``, ``SimulatedBus.transfer``) in the namespace of the module (and class)
  whose docstring or page holds the reference.

It then looks for the documented object that *is* that object (``is``, not equal) and links
there. A name that imports nothing, or an object the API pages do not document (a private name),
stays unresolved and the nitpicky build reports it: nothing is hidden.

A module and a function may share a name: ``ebantenna.study`` re-exports the function
``reproduce`` of its module ``reproduce``. autosummary reads ``ebantenna.study.reproduce`` as the
function first, and the module's page then documents only the function; so this extension makes
autosummary take a name that is an importable module as that module.
"""

from __future__ import annotations

import importlib
import importlib.util

import sphinx.ext.autosummary as autosummary
from docutils import nodes
from sphinx.addnodes import pending_xref

_MISSING = object()


def import_name(dotted: str):
    """The object ``dotted`` names, or ``_MISSING``: the longest importable module, then attributes.

    Parameters
    ----------
    dotted : str
        A dotted Python name such as ``"ebantenna.signal.fit_decay"``.
    """
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        except Exception:  # a module that fails on import is no target either
            return _MISSING
        for attr in parts[k:]:
            obj = getattr(obj, attr, _MISSING)
            if obj is _MISSING:
                return _MISSING
        return obj
    return _MISSING


def candidates(target: str, module: str | None, cls: str | None) -> list[str]:
    """The full dotted names ``target`` may stand for, seen from ``module`` (and class ``cls``)."""
    if target.startswith("ebantenna."):
        return [target]
    names = []
    if module and module.startswith("ebantenna"):
        if cls:
            names.append(f"{module}.{cls}.{target}")
        names.append(f"{module}.{target}")
    return names


def same(a, b) -> bool:
    """Whether ``a`` and ``b`` are one object; a method bound anew on each access counts as one."""
    return a is b or (hasattr(a, "__func__") and getattr(b, "__func__", None) is a.__func__)


def documented_name(obj, tail: str, documented) -> str | None:
    """The documented full name whose object is ``obj`` itself and whose last parts are ``tail``.

    Parameters
    ----------
    obj : object
        What the reference's name imports to.
    tail : str
        The last one or two parts of the name as written (``"fit_decay"``, ``"SVC.fit"``).
    documented : iterable of str
        The Python objects the build documents.
    """
    own = getattr(obj, "__qualname__", None)
    home = getattr(obj, "__module__", None)
    if own and home:
        name = f"{home}.{own}"
        if name in documented and same(import_name(name), obj):
            return name
    for name in documented:
        if name.startswith("ebantenna.") and name.endswith("." + tail):
            if same(import_name(name), obj):
                return name
    return None


def resolve_public_name(app, env, node, contnode):
    """``missing-reference`` handler: link a re-exported or module-local name to its page."""
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"]
    domain = env.get_domain("py")
    documented = {name for name, *_rest in domain.get_objects()}
    for full in candidates(target, node.get("py:module"), node.get("py:class")):
        obj = import_name(full)
        if obj is _MISSING:
            continue
        parent, _, last = full.rpartition(".")
        # a class member keeps its class in the tail, so that SVC.fit never links MLP.fit
        member = isinstance(import_name(parent), type)
        tail = f"{parent.rpartition('.')[2]}.{last}" if member else last
        name = documented_name(obj, tail, documented)
        if name is None:
            continue
        new = pending_xref("", refdomain="py", reftype=node["reftype"], reftarget=name,
                           refexplicit=True, refwarn=True)
        new["py:module"] = new["py:class"] = None
        found = domain.resolve_xref(env, node.get("refdoc", ""), app.builder, node["reftype"],
                                    name, new, contnode)
        if isinstance(found, nodes.Element):
            return found
    return None


def module_first(import_by_name):
    """Wrap autosummary's importer so that a name which is a module is imported as that module."""

    def wrapped(name: str, grouped_exception: bool = True):
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            spec = None
        if spec is not None:
            return importlib.import_module(name), None, name
        return import_by_name(name, grouped_exception)

    wrapped.original = import_by_name
    return wrapped


def setup(app):
    if not hasattr(autosummary._import_by_name, "original"):
        autosummary._import_by_name = module_first(autosummary._import_by_name)
    app.connect("missing-reference", resolve_public_name)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
