"""benchmarks/network_epoch_floor.py: its floor is an epoch's own arithmetic (the gradient the
package's backpropagation gives), and the script runs and refuses bad sizes by name."""

import benchmark_scripts
import numpy as np
import pytest

from ebantenna.ml.backprop import loss_and_gradients

floor = benchmark_scripts.load("network_epoch_floor")


def test_the_floor_computes_the_epochs_gradient():
    # the timed floor must do an epoch's work, not less: its summed weight gradients over the
    # rows are n times backprop's (mean loss), up to the rounding of sums of n products
    rng = np.random.default_rng(3)
    n, d, h, k = 40, 7, 5, 3
    X = rng.standard_normal((n, d))
    Y = np.eye(k)[rng.integers(0, k, n)]
    W1, W2 = rng.standard_normal((d, h)), rng.standard_normal((h, k))
    b1, b2 = rng.standard_normal(h), rng.standard_normal(k)
    G1, G2 = floor.epoch_products(X, Y, W1, b1, W2, b2)()
    _, (g1, g2), _ = loss_and_gradients(X, Y, [W1, W2], [b1, b2], "tanh", "softmax", alpha=0.0)
    eps = np.finfo(float).eps
    # an entry is a sum of n products |left| |error|, each error below 1 + sum |W2| (the
    # softmax's below 1, carried back through W2): the sums round within n eps times that,
    # over n for the mean; 64 covers the forward pass's own rounding in the errors
    bound = 64 * n * eps * (1 + np.abs(W2).sum())
    for G, g, left in ((G1, g1, X), (G2, g2, np.tanh(X @ W1 + b1))):
        np.testing.assert_allclose(G / n, g, rtol=0, atol=bound * np.abs(left).max())


def test_the_script_prints_its_three_parts(capsys):
    floor.main(["--rows", "30", "--features", "6", "--hidden", "4", "--classes", "3",
                "--repeats", "2", "--epochs", "10"])
    out = capsys.readouterr().out
    for part in ("epoch (MLPClassifier.fit", "validation pass", "products alone (floor)",
                 "the estimator's share of an epoch"):
        assert part in out


@pytest.mark.parametrize(("args", "name"), [
    (["--rows", "0"], "--rows"), (["--repeats", "-1"], "--repeats"),
    (["--classes", "1"], "--classes"), (["--rows", "3", "--classes", "5"], "--classes"),
])
def test_bad_sizes_are_refused_by_name(args, name, capsys):
    with pytest.raises(SystemExit):
        floor.main(args)
    assert name in capsys.readouterr().err
