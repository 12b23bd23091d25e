"""A forged data set whose checksum was recomputed is still refused when its rows disagree.

The checksum catches a file changed by accident; someone who knows the format can recompute it.
Rows of different lengths (``material`` shorter than ``ax``), a 1-D signal array, NaN signals, a
negative contact distance, a fractional repetition, a sample rate or a probe length that is not
positive (or absent) must end in one error naming the file, not an ``IndexError`` or a
``KeyError`` in the study that reads it.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from ebantenna.simulate import load_dataset
from ebantenna.simulate.dataset import FORMAT, _checksum

N, S = 4, 64


def _arrays():
    rng = np.random.default_rng(0)
    return {"ax": rng.normal(size=(N, S)).astype(np.float32),
            "az": rng.normal(size=(N, S)).astype(np.float32),
            "material": np.array(["brass", "pvc"] * (N // 2)),
            "contact": np.full(N, 0.1), "contact_true": np.full(N, 0.1),
            "repetition": np.arange(N, dtype=np.int64), "sweep_speed": np.full(N, np.nan),
            "tilt_ratio": np.full(N, np.nan), "seed_row": np.full(N, -1, dtype=np.int64)}


PROBE = {"probe": {"length": 0.4}}


def _write(path, fs=1000.0, scene=PROBE, **changes):
    arrays = {**_arrays(), **changes}
    config = {"format": FORMAT} if scene is None else {"format": FORMAT, "scene": scene}
    meta = {"config": config, "checksum_sha256": _checksum(arrays, fs)}
    np.savez(path, fs=np.float64(fs), metadata=np.array(json.dumps(meta)), **arrays)
    return path


ROWS = {
    "material-short": ({"material": np.array(["brass"] * (N - 1))}, "material"),
    "contact-long": ({"contact": np.full(N + 3, 0.1)}, "contact"),
    "ax-1d": ({"ax": np.zeros(S, np.float32), "az": np.zeros(S, np.float32)}, "ax"),
    "az-other-shape": ({"az": np.zeros((N, S + 1), np.float32)}, "az"),
    "ax-nan": ({"ax": np.full((N, S), np.nan, np.float32)}, "ax"),
    "contact-negative": ({"contact": np.full(N, -0.1)}, "contact"),
    "repetition-fraction": ({"repetition": np.full(N, 1.5)}, "repetition"),
    "material-numbers": ({"material": np.arange(N)}, "material"),
    "fs-zero": ({"fs": 0.0}, "fs"),
    "fs-nan": ({"fs": float("nan")}, "fs"),
    "no-scene": ({"scene": None}, "probe's length"),
    "probe-length-negative": ({"scene": {"probe": {"length": -0.4}}}, "probe's length"),
    "probe-length-text": ({"scene": {"probe": {"length": "0.4"}}}, "probe's length"),
}


@pytest.mark.parametrize("case", ROWS)
def test_a_forged_data_set_is_refused_naming_the_file(tmp_path, case):
    changes, word = ROWS[case]
    path = _write(tmp_path / "d.npz", **changes)
    with pytest.raises(ValueError) as caught:
        load_dataset(path)
    assert str(path) in str(caught.value) and word in str(caught.value), caught.value


def test_the_unforged_file_loads_equal(tmp_path):
    data = load_dataset(_write(tmp_path / "d.npz"))
    assert data.n_signals == N and data.material.tolist() == ["brass", "pvc"] * 2
    np.testing.assert_array_equal(data.ax, _arrays()["ax"])


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {"ebantenna.simulate.dataset.load_dataset": list(ROWS), "file:dataset": list(ROWS)}
