"""One test for each kind of file fault that the loaders and savers refuse, by name."""

import json
import os
import threading
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest
from unloaded_time import time_limit

from ebantenna import MemoryBudgetError, Recording
from ebantenna._validate import MAX_JSON_DEPTH, json_depth, open_regular, output_dir, output_path
from ebantenna.ml import SVC, MLPClassifier, load_model, persistence, save_model
from ebantenna.simulate import builtin_scene
from ebantenna.simulate.scene import load_scene

X = np.random.default_rng(0).normal(size=(30, 2))
Y = (X[:, 0] > 0).astype(int)


def _recording(tmp_path) -> Path:
    t = np.arange(8) / 100.0
    return Recording(t, np.sin(t), np.cos(t), 100.0, {"seed": 1}).save(tmp_path / "rec")


def _rewrite_model(path, change=None, *, checksum=False, **arrays):
    with np.load(path, allow_pickle=False) as data:
        stored = {k: data[k] for k in data.files}
    meta = json.loads(str(stored.pop("__meta__")))
    if change is not None:
        change(meta)
    stored.update(arrays)
    if checksum:
        meta["checksum_sha256"] = persistence._checksum(stored, meta)
    np.savez(path, __meta__=np.array(json.dumps(meta)), **stored)


def test_a_header_declaring_2_to_the_40_values_is_refused_naming_the_file(tmp_path):
    path = _recording(tmp_path)
    with zipfile.ZipFile(path) as archive:
        members = {i.filename: archive.read(i) for i in archive.infolist()}
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (1099511627776,), }"
    header += " " * (118 - len(header)) + "\n"  # 10 + 118 = 128 bytes, as NumPy aligns it
    members["ax.npy"] = b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + \
        header.encode() + bytes(64)
    with zipfile.ZipFile(path, "w") as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    with pytest.raises(MemoryBudgetError, match=f"the file {path} asks for its array 'ax'"):
        Recording.load(path)


@pytest.mark.parametrize("load", [Recording.load, load_model, load_scene])
def test_a_fifo_is_refused_at_once_instead_of_blocking(tmp_path, load):
    fifo = tmp_path / "pipe.npz"
    os.mkfifo(fifo)
    # a blocked open would wait for a writer, forever: 5 s of the test's own time (blocked
    # time counts, waits for a CPU do not) turns that into a failure
    with pytest.raises(ValueError, match=f"{fifo} is a FIFO"), time_limit(5, TimeoutError):
        load(fifo)


def test_a_fifo_swapped_in_after_the_check_is_refused_not_waited_on(tmp_path, monkeypatch):
    regular, fifo = tmp_path / "file", tmp_path / "fifo"
    regular.write_bytes(b"x")
    os.mkfifo(fifo)
    real_stat = os.stat
    # the first look sees a regular file; the open then meets the FIFO (a race lost)
    monkeypatch.setattr(os, "stat", lambda p, *a, **k: real_stat(regular if p == fifo else p))
    with pytest.raises(ValueError, match="is a FIFO"):
        open_regular(fifo, "a recording")


def test_deep_json_is_refused_without_recursion_error(tmp_path):
    assert json_depth('{"a": ["]", {"b": [[]]}]}') == 5
    scene = tmp_path / "deep.json"
    scene.write_text("[" * 200_000 + "]" * 200_000)
    with pytest.raises(ValueError, match=f"{scene} is not a scene file: its JSON nests 200000"):
        load_scene(scene)
    toml = tmp_path / "deep.toml"
    toml.write_text("a = " + "[" * 5000 + "]" * 5000)
    with pytest.raises(ValueError, match=f"{toml}: not valid TOML"):
        load_scene(toml)
    ok = tmp_path / "ok.json"
    ok.write_text("[" * MAX_JSON_DEPTH + "]" * MAX_JSON_DEPTH)  # at the limit: parsed
    with pytest.raises(ValueError, match="holds one table/object, not a list"):
        load_scene(ok)


def test_a_binary_scene_file_is_named(tmp_path):
    path = tmp_path / "scene.json"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\xff")
    with pytest.raises(ValueError, match=f"{path} is not a scene file: it is not UTF-8 text"):
        load_scene(path)


@pytest.mark.parametrize("load", [Recording.load, load_model, load_scene])
def test_paths_are_str_or_pathlike_only(tmp_path, load):
    with pytest.raises(TypeError, match="path must be a str or os.PathLike, got bytes"):
        load(str(tmp_path / "x.npz").encode())
    with pytest.raises(ValueError, match="path holds a NUL character"):
        load(str(tmp_path / "x\0.npz"))
    with pytest.raises(TypeError, match="path must be a str or os.PathLike, got int"):
        load(3)


def test_a_proc_output_is_not_reported_as_a_missing_file(tmp_path):
    with pytest.raises(OSError, match="cannot write in /proc: it does not accept new files"):
        output_path("--out", "/proc/rec.npz", ".npz")
    with pytest.raises(FileNotFoundError, match="the directory .*nowhere does not exist"):
        output_path("--out", tmp_path / "nowhere" / "rec", ".npz")
    with pytest.raises(NotADirectoryError, match="--out must be a directory"):
        output_dir("--out", _recording(tmp_path))
    assert output_dir("--out", tmp_path / "a" / "b") == tmp_path / "a" / "b"
    assert not (tmp_path / "a").exists()  # checked, not made
    assert os.listdir(tmp_path) == ["rec.npz"]  # the write test leaves nothing behind


def test_an_output_fifo_is_refused_instead_of_blocking_the_writer(tmp_path):
    fifo = tmp_path / "out.npz"
    os.mkfifo(fifo)
    t = np.arange(4) / 10.0
    with pytest.raises(ValueError, match="path must name a regular file.*FIFO"):
        Recording(t, t, t, 10.0).save(fifo)


def _svc(tmp_path):
    model = SVC(C=3.0).fit(X, Y)
    return model, save_model(model, tmp_path / "m")


@pytest.mark.parametrize("version", [1, 2, True, 3.0, "4"])
def test_editing_the_version_cannot_skip_the_checksum(tmp_path, version):
    model, path = _svc(tmp_path)
    _rewrite_model(path, lambda m: m.update(format_version=version),
                   dual_coef_=-model.dual_coef_)
    expected = "checksum mismatch" if type(version) is int else "unsupported format version"
    with pytest.raises(ValueError, match=f"m.npz: {expected}"):
        load_model(path)


def test_a_legacy_file_without_checksum_loads_only_when_asked(tmp_path):
    model, path = _svc(tmp_path)

    def as_version_2(meta):
        meta["format_version"] = 2
        del meta["checksum_sha256"]

    _rewrite_model(path, as_version_2)
    with pytest.raises(ValueError, match="format 2 carries no checksum.*unchecked=True"):
        load_model(path)
    again = load_model(path, unchecked=True)
    np.testing.assert_array_equal(again.decision_function(X), model.decision_function(X))


def _mlp():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return MLPClassifier((3,), max_iter=10, random_state=0).fit(X, Y)


def test_format_4_requires_loss_and_format_3_files_still_load(tmp_path):
    model = _mlp()
    path = save_model(model, tmp_path / "mlp")
    with np.load(path) as data:
        assert json.loads(str(data["__meta__"]))["format_version"] == 4
    assert load_model(path).loss_ == model.loss_
    _rewrite_model(path, lambda m: m["attributes"].pop("loss_"), checksum=True)
    with pytest.raises(ValueError, match="mlp.npz: the fitted attribute loss_ .* is missing"):
        load_model(path)

    def as_version_3(meta):  # a format 3 file, written before loss_ was kept
        meta["format_version"] = 3

    _rewrite_model(path, as_version_3, checksum=True)
    old = load_model(path)
    assert not hasattr(old, "loss_")
    np.testing.assert_array_equal(old.predict_proba(X), model.predict_proba(X))
    with pytest.raises(ValueError, match="lacks its fitted attribute loss_"):
        save_model(old, tmp_path / "again")  # format 4 is never written without it


def test_valid_files_load_equal_to_what_was_saved(tmp_path):
    path = _recording(tmp_path)
    rec = Recording.load(path)
    again = Recording.load(_PathLike(str(path)))
    assert rec.metadata == again.metadata == {"seed": 1}
    np.testing.assert_array_equal(rec.ax, again.ax)
    scene = builtin_scene("paper")
    assert load_scene(scene.save(tmp_path / "s.toml")).to_dict() == scene.to_dict()


class _PathLike:
    def __init__(self, text):
        self.text = text

    def __fspath__(self):
        return self.text


def test_loading_a_fifo_does_not_hang_even_with_a_writer_waiting(tmp_path):
    """A writer that opens the FIFO gets no reader: the loader never opened it."""
    fifo = tmp_path / "p.npz"
    os.mkfifo(fifo)
    done = threading.Event()

    def writer():
        try:
            fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)  # ENXIO: nobody reads
            os.close(fd)
        except OSError:
            done.set()

    with pytest.raises(ValueError, match="FIFO"):
        Recording.load(fifo)
    thread = threading.Thread(target=writer)
    thread.start()
    thread.join(5)
    assert done.is_set()
