"""The input contract of the output paths of the data-set builders and the studies: checked
before any work.

Every path a builder writes (``out_dir`` of :func:`~ebantenna.simulate.build_dataset`,
:func:`~ebantenna.simulate.build_datasets` and :func:`~ebantenna.paper.data.build_paper_dataset`,
``--out`` of ``ebantenna dataset``) is refused, naming the parameter, when it is not a path,
when a file stands where the directory goes, when the directory cannot be written, and when a
directory stands where the data set's file goes. The rows that build the paper's full
design (about 10,000 simulated signals: minutes of work) end within the row's time limit, so
the refusal comes before the simulation. :func:`~ebantenna.simulate.dataset.dataset_path`, the
check itself, is held to the file the builder writes. The studies (:func:`~ebantenna.study.
reproduce`, :func:`~ebantenna.study.recorded.study.reproduce_recorded`, ``ebantenna
reproduce --out``) refuse their folder likewise, and a directory where their report or
summary goes, before minutes to hours of work.
"""

from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests, run_cli  # noqa: E402

from ebantenna.paper.data import PAPER_DESIGN, build_paper_dataset  # noqa: E402
from ebantenna.simulate import DatasetDesign, build_dataset, build_datasets, builtin_scene  # noqa: E402, E501
from ebantenna.simulate.dataset import dataset_path  # noqa: E402
from ebantenna.study.recorded.study import reproduce_recorded  # noqa: E402
from ebantenna.study.reproduce import reproduce  # noqa: E402

#: One brass signal at 0.3 m: the smallest data set.
ONE = DatasetDesign("one", ("brass",), 0.3, 0.1, 1)
#: The paper's file name for the full design and seed 0.
PAPER_FILE = f"paper-{PAPER_DESIGN.name}-seed0.npz"


def _folder() -> Path:
    """A new scratch folder (removed when the process ends)."""
    where = Path(tempfile.mkdtemp(prefix="eb-paths-"))
    _KEEP.append(where)
    return where


_KEEP: list[Path] = []
atexit.register(lambda: [shutil.rmtree(p, ignore_errors=True) for p in _KEEP])


def _with_directory_at(name: str) -> Path:
    """A folder holding a directory named ``name``, where a data set's file goes."""
    where = _folder()
    (where / name).mkdir()
    return where


def _with_fifo_at(name: str) -> Path:
    where = _folder()
    os.mkfifo(where / name)
    return where


def _a_file() -> Path:
    path = _folder() / "a-file"
    path.write_text("not a folder")
    return path


def _full_paper(out_dir):
    """The paper's full design: refused before minutes of simulation, or the row times out."""
    return build_dataset(out_dir, builtin_scene("paper"), PAPER_DESIGN, 0, show_progress=False)


def _two_scenes():
    paper = builtin_scene("paper")
    return [paper, paper.with_(name="paper-b")]


def _built_where_checked():
    """``(dataset_path's answer, the path build_dataset wrote)`` for one small data set."""
    where = _folder()
    scene = builtin_scene("ideal")
    expected = dataset_path(where, scene, ONE, 7)
    return expected, build_dataset(where, scene, ONE, 7, show_progress=False).path


def all_rows():
    d = "ebantenna.simulate.dataset."
    paper = "ebantenna.paper.data.build_paper_dataset"
    scene = builtin_scene("paper")
    return [
        Row(d + "build_dataset", "out_dir-int", lambda: build_dataset(5, scene, ONE),
            ("out_dir",)),
        Row(d + "build_dataset", "out_dir-bytes", lambda: build_dataset(b"d", scene, ONE),
            ("out_dir",)),
        Row(d + "build_dataset", "out_dir-empty", lambda: build_dataset("", scene, ONE),
            ("out_dir",)),
        Row(d + "build_dataset", "out_dir-a-file", lambda: _full_paper(_a_file()),
            ("out_dir",)),
        Row(d + "build_dataset", "out_dir-in-proc", lambda: _full_paper("/proc/eb-dataset"),
            ("out_dir",)),
        Row(d + "build_dataset", "a-directory-where-the-file-goes",
            lambda: _full_paper(_with_directory_at(PAPER_FILE)), ("out_dir",)),
        Row(d + "build_datasets", "a-directory-where-the-second-file-goes",
            lambda: build_datasets(_with_directory_at(f"paper-b-{PAPER_DESIGN.name}-seed0.npz"),
                                   _two_scenes(), PAPER_DESIGN, show_progress=False),
            ("out_dir",)),
        Row(d + "build_datasets", "a-scene-name-with-a-slash",
            lambda: build_datasets(_folder(), [scene.with_(name="../escaped")], PAPER_DESIGN),
            ("scene",)),
        Row(paper, "out_dir-int", lambda: build_paper_dataset(5), ("out_dir",)),
        Row(paper, "a-directory-where-the-file-goes",
            lambda: build_paper_dataset(_with_directory_at(PAPER_FILE), show_progress=False),
            ("out_dir",)),
        Row(d + "dataset_path", "scene-str", lambda: dataset_path(_folder(), "paper", ONE),
            ("scene",)),
        Row(d + "dataset_path", "design-None", lambda: dataset_path(_folder(), scene, None),
            ("design",)),
        Row(d + "dataset_path", "seed-negative", lambda: dataset_path(_folder(), scene, ONE, -1),
            ("seed",)),
        Row(d + "dataset_path", "scene-named-dot-dot",
            lambda: dataset_path(_folder(), scene.with_(name=".."), ONE), ("scene",)),
        Row(d + "dataset_path", "named-as-the-command-names-it",
            lambda: dataset_path(_with_directory_at("paper-one-seed0.npz"), scene, ONE,
                                 parameter="--out"), ("--out",)),
        # a directory that does not exist yet is fine: the builder makes it
        Row(d + "dataset_path", "a-new-directory",
            lambda: (lambda w: (dataset_path(w / "new" / "deeper", scene, ONE, 3), w))(_folder()),
            same=lambda r: r[0] == r[1] / "new" / "deeper" / "paper-one-seed3.npz"),
        # written whole and renamed into place, the file replaces a FIFO (as a damaged cache)
        Row(d + "dataset_path", "a-fifo-where-the-file-goes-is-replaced",
            lambda: (lambda w: (dataset_path(w, scene, ONE), w))(
                _with_fifo_at("paper-one-seed0.npz")),
            same=lambda r: r[0] == r[1] / "paper-one-seed0.npz"),
        Row(d + "dataset_path", "the-file-build_dataset-writes", _built_where_checked,
            same=lambda r: r[0] == r[1] and r[1].is_file()),
        Row("cli:dataset --out", "a-directory-where-the-file-goes",
            lambda: run_cli(["dataset", "--out", str(_with_directory_at(PAPER_FILE))]),
            ("--out",)),
        Row("cli:dataset --out", "a-file",
            lambda: run_cli(["dataset", "--out", str(_a_file())]), ("--out",)),
        *_study_rows(),
    ]


def _study_rows():
    r = "ebantenna.study.reproduce.reproduce"
    rec = "ebantenna.study.recorded.study.reproduce_recorded"
    nowhere = "/nonexistent/data.npz"  # the folder is refused before the data are read
    return [
        Row(r, "out_dir-int", lambda: reproduce(5, quick=True, cache_dir=_folder()),
            ("out_dir",)),
        Row(r, "out_dir-bytes", lambda: reproduce(b"out", quick=True, cache_dir=_folder()),
            ("out_dir",)),
        Row(r, "out_dir-a-file", lambda: reproduce(_a_file(), quick=True, cache_dir=_folder()),
            ("out_dir",)),
        # the full study runs for hours: refused within the row's time limit
        Row(r, "a-directory-where-summary.json-goes",
            lambda: reproduce(_with_directory_at("summary.json"), cache_dir=_folder()),
            ("out_dir",)),
        Row(r, "cache_dir-a-file", lambda: reproduce(_folder(), cache_dir=_a_file()),
            ("cache_dir",)),
        Row(rec, "out_dir-int", lambda: reproduce_recorded(nowhere, 5), ("out_dir",)),
        Row(rec, "a-directory-where-report.html-goes",
            lambda: reproduce_recorded(nowhere, _with_directory_at("report.html")),
            ("out_dir",)),
        Row("cli:reproduce --out", "a-directory-where-summary.json-goes",
            lambda: run_cli(["reproduce", "--out", str(_with_directory_at("summary.json")),
                             "--cache", str(_folder())]), ("--out",)),
    ]


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, "ebantenna.simulate.")
