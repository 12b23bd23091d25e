"""`Recording` files: the path written is the path returned; damage ends in one clear error."""

import json
import os

import numpy as np
import pytest

from ebantenna.recording import Recording

REC = Recording(np.arange(3) / 1e3, [0.0, 1.0, -1.0], [0.5, 0.0, 0.25], 1e3, {"seed": 3})


def test_save_returns_the_file_numpy_writes_and_it_loads_bit_for_bit(tmp_path):
    path = REC.save(tmp_path / "take")
    assert path == tmp_path / "take.npz" and sorted(os.listdir(tmp_path)) == ["take.npz"]
    again = Recording.load(path)
    assert again.ax.tobytes() == REC.ax.tobytes() and again.metadata == {"seed": 3}


@pytest.mark.parametrize("name", ["", ".", "sub", "sub/"])
def test_save_refuses_a_directory_or_an_empty_name(tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    os.mkdir("sub")
    with pytest.raises(ValueError, match="path must name a file"):
        REC.save(name)
    assert os.listdir(tmp_path) == ["sub"] and os.listdir("sub") == []


def arrays(**changes):
    base = {
        "t": REC.t,
        "ax": REC.ax,
        "az": REC.az,
        "fs": np.float64(1e3),
        "metadata": np.array(json.dumps({})),
    }
    base.update(changes)
    return {k: v for k, v in base.items() if v is not None}


@pytest.mark.parametrize(
    "content, match",
    [
        (b"", "the file is empty"),
        (b"\x93NUMPY", "not an .npz archive"),
        (arrays(az=None), "lacks the array 'az"),
        (arrays(ax=np.zeros(5)), "same length"),
        (arrays(fs=np.zeros(2)), "fs must be one number"),
        (arrays(fs=np.float64(-1.0)), "fs must be > 0"),
        (arrays(metadata=np.array("[1, 2]")), "metadata must be a JSON object"),
        (arrays(metadata=np.array("{oops")), "Expecting property name"),
        (arrays(t=np.array([0.0, np.nan, 1.0])), "finite"),
    ],
)
def test_a_damaged_or_foreign_file_names_itself_and_the_fault(tmp_path, content, match):
    path = tmp_path / "r.npz"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        np.savez(path, **content)
    with pytest.raises(ValueError, match=match) as exc:
        Recording.load(path)
    assert str(path) in str(exc.value)


@pytest.mark.parametrize("header", [
    b"{'descr': '<f8', 'fortran_order': False, 'shape': (3,), ",  # a brace left open
    b"{'descr': '<f8', 'fortran_order': False, 'shape': (3,)) }",  # one too many
])
def test_an_array_header_that_is_no_literal_names_the_file(tmp_path, header):
    # NumPy parses a version-1 header as a literal and, failing, tokenizes it as one written by
    # Python 2: an unbalanced bracket then escapes as tokenize's TokenError or a SyntaxError
    # (a single bit flipped in a data set's header did)
    import zipfile

    from numpy.lib import format as npformat

    body = header.ljust(117) + b"\n"  # padded so that magic, length and header fill 128 bytes
    member = npformat.magic(1, 0) + len(body).to_bytes(2, "little") + body + bytes(24)
    path = tmp_path / "r.npz"
    np.savez(path, **arrays())
    with zipfile.ZipFile(path, "a") as z:
        z.writestr("zz.npy", member)  # a member every load opens to check its size
    with pytest.raises(ValueError, match="r.npz is not a recording") as exc:
        Recording.load(path)
    assert str(path) in str(exc.value)


def test_a_truncated_file_and_a_missing_one(tmp_path):
    path = REC.save(tmp_path / "r.npz")
    os.truncate(path, path.stat().st_size - 20)
    with pytest.raises(ValueError, match="r.npz is not a recording"):
        Recording.load(path)
    with pytest.raises(FileNotFoundError):
        Recording.load(tmp_path / "none.npz")
