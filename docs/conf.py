"""Sphinx configuration of the ebantenna documentation.

Build from the repository root::

    python -m sphinx -W --keep-going -b html docs docs/_build/html
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE / "_tools"))

from make_inventories import intersphinx_mapping as _local_inventories  # noqa: E402

import ebantenna  # noqa: E402

project = "ebantenna"
author = "The ebantenna developers"
copyright = "the ebantenna developers, BSD-3-Clause"
release = ebantenna.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    # MathJax 3 itself (scripts and fonts), copied from its PyPI package into _static/mathjax: the
    # pages typeset their formulas with no network (a classroom offline, the rig's Raspberry Pi)
    "sphinx-mathjax-offline",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "matplotlib.sphinxext.plot_directive",
    "ebantenna_docs",
    "paper_map",
    "study_tables",
    "exercise_notebooks",
    # a reference may use the name a user imports (ebantenna.signal.fit_decay): linked to the page
    # of the very object it imports to, in the module that defines it
    "public_names",
    "course_tracks",
]

templates_path = ["_templates"]
exclude_patterns = [
    "_build", "_inventories", "_tools", "_ext", "exercises/solutions",
    "examples/GALLERY_HEADER.rst",
    # timing pages an older build with write_computation_times on may have left in the tree
    "sg_execution_times.rst", "auto_examples/sg_execution_times.rst",
]
html_theme = "furo"
html_title = f"ebantenna {release}"
html_static_path = ["_static"]
html_css_files = ["ebantenna.css"]

# --- API reference -----------------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {
    "members": True,
    "inherited-members": False,
    "show-inheritance": False,
    # scikit-learn's metadata-routing helpers, generated on every estimator: not ours to document
    "exclude-members": (
        "set_fit_request,set_partial_fit_request,set_score_request,set_predict_request,set_output"
    ),
}
autodoc_typehints = "none"  # numpydoc docstrings already say the types, with units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = True
numpydoc_xref_aliases = {
    "Probe": "ebantenna.probe.Probe",
    "Recording": "ebantenna.recording.Recording",
    "Supports": "ebantenna.fem.assembly.Supports",
    "ModalResult": "ebantenna.fem.modal.ModalResult",
    "ZoneResult": "ebantenna.fem.zones.ZoneResult",
    "Erratum": "ebantenna.fem.symbolic.Erratum",
    "Material": "ebantenna.probe.Material",
    "Rod": "ebantenna.fem.coupling.Rod",
    "Scene": "ebantenna.simulate.scene.Scene",
    "SystemClock": "ebantenna.device.clock.SystemClock",
    "VirtualClock": "ebantenna.device.clock.VirtualClock",
    "ClassificationResult": "ebantenna.paper.experiments.ClassificationResult",
    "RegressionResult": "ebantenna.paper.experiments.RegressionResult",
    "ndarray": "numpy.ndarray",
    "Axes": "matplotlib.axes.Axes",
    "Matrix": "sympy.Matrix",
    "object": "object",
    # numpydoc's defaults point these at glossaries of inventories we do not keep
    "bool": "bool",
    "sequence": "collections.abc.Sequence",
    "iterable": "collections.abc.Iterable",
    "module": "types.ModuleType",
    "array_like": "numpy.typing.ArrayLike",
    "array-like": "numpy.typing.ArrayLike",
    "Generator": "numpy.random.Generator",
    "RandomState": "numpy.random.RandomState",
    "Path": "pathlib.Path",
    "dtype": "numpy.dtype",
    "int16": "numpy.int16",
    "int32": "numpy.int32",
    "int64": "numpy.int64",
    "float32": "numpy.float32",
    "float64": "numpy.float64",
    "csr_matrix": "scipy.sparse.csr_matrix",
}
# The vocabulary of a type description, which names no object: linking words, the kinds of
# container ("array", "matrix"), the sizes in a shape ("n_samples", "k") and the names of the parts
# of a tuple ("(key, header, format)"). Python's own types ("int", "float", "dict"...) are not in
# this list: numpydoc links them to the Python inventory.
numpydoc_xref_ignore = {
    # linking words
    "of", "or", "and", "to", "as", "for", "from", "the", "a", "else", "otherwise", "given", "two",
    "shape", "shapes", "optional", "default", "compatible", "instance", "instances", "classes",
    # kinds of container and value
    "array", "arrays", "ndarrays", "dense", "sparse", "matrix", "matrices", "CSR", "scalar",
    "any", "inf", "self", "estimator", "path", "path-like", "numpy", "4x4", "6x6",
    "matplotlib", "sympy",
    # sizes in a shape
    "n", "m", "k", "p", "N", "n_SV", "n_bins", "n_classes", "n_contacts", "n_distances",
    "n_elements", "n_features", "n_fft", "n_freqs", "n_int", "n_labels", "n_modes", "n_nodes",
    "n_outputs", "n_pairs", "n_recordings", "n_rods", "n_samples", "n_sections", "n_signals",
    "n_states", "n_terms", "n_times",
    # names of the parts of a tuple
    "key", "header", "format", "field", "low", "high", "time", "axis", "angle", "address",
    "register",
}

# --- Links to the libraries, from inventories kept in the repository (no download) -------------
intersphinx_mapping = _local_inventories("_inventories")
intersphinx_timeout = 1

# --- Gallery: every example runs at build time, so its figures cannot go stale ------------------
os.environ.setdefault("MPLBACKEND", "Agg")
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"__init__\.py",
    # every example also as a notebook and a script, and all of them in one zip
    "download_all_examples": True,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "show_memory": False,
    # the timing page loads DataTables from a CDN, and its numbers change every build: not written
    "write_computation_times": False,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "doc_module": ("ebantenna",),
    "reference_url": {"ebantenna": None},
    "backreferences_dir": None,
    # matplotlib's scraper, after docs/_ext/figure_check.py found every axis labelled, no panel
    # empty, no legend entry without its curve and no log axis reaching far beyond its data
    "image_scrapers": ("figure_check",),
}

math_number_all = False

# --- Every cross-reference must land: the -W build fails on a target that has no page ---------
nitpicky = True
# Only objects that exist but have no page, because they live in a private module:
nitpick_ignore = {
    # the base every effect shows as "Bases: Effect" (a name, parameters as a dict, construction
    # from a dict), in the private ebantenna.simulate.effects._base
    ("py:class", "ebantenna.simulate.effects._base.Effect"),
    # the record windowed_spectrum returns, from the private ebantenna.signal._guards; its fields
    # are described where it is returned
    ("py:obj", "AnalysedPart"),
}

# --- Figures drawn by the package inside a page (``.. plot::``), such as the probe's sketch ------
plot_include_source = False
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 110)]
plot_rcparams = {"figure.autolayout": True}

# --- Editions: students by default, teachers with ``-t teacher`` -------------------------------
# The teacher edition (python -m sphinx -t teacher -b html docs docs/_build/teacher) adds the
# exercises' expected answers and worked solutions (``.. teacher::`` blocks, never parsed in the
# student edition). Its reST sources hold those blocks, so only it copies them into _sources/.
exercise_edition = "teacher" if tags.has("teacher") else "student"  # noqa: F821 (Sphinx's tags)
html_copy_source = exercise_edition == "teacher"
html_show_sourcelink = html_copy_source
html_theme_options = {
    "announcement": (
        "Teacher edition: expected answers and worked solutions shown. Not for students."
        if exercise_edition == "teacher"
        else "Student edition: exercises with self-checks, no solutions."
    ),
}
