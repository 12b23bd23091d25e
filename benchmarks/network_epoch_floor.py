"""The paper network's epoch against the arithmetic it cannot avoid, measured in one run.

The study's ``ml`` step waits for the paper's network (``learning.ANN_MAX_EPOCHS`` epochs of
full-batch gradient descent, MATLAB's traingd, in ``paper.experiments.classify_materials_ann``):
its other fits end long before, so the network's epochs are the step's critical path. Each epoch
must multiply the training rows through both layers and back (four matrix products) and take
the activations and the softmax; everything else is the estimator's: the check of its input at
every call (``warm_start`` continues the fit one epoch per call), the labels' encoding, and the
validation pass that MATLAB's validation check also makes.

This script times, on random data of the paper's shapes (the cost of an epoch of gradient
descent does not depend on the values), the median over ``--repeats`` of:

- ``epoch``: one call of :class:`ebantenna.ml.MLPClassifier` ``.fit`` with ``warm_start``, as the
  experiment makes it;
- ``validation``: its ``predict_log_proba`` on the validation rows;
- ``products``: the epoch's forward and backward products, the tanh and the softmax, written
  directly in NumPy with preallocated arrays: the floor of an epoch in NumPy.

Run from the repository: ``python benchmarks/network_epoch_floor.py`` (``--help``).
"""

import argparse
import inspect
import time
import warnings

import numpy as np

from ebantenna._threads import limited_threads
from ebantenna.ml import MLPClassifier
from ebantenna.paper.experiments import classify_materials_ann
from ebantenna.paper.protocol import MATERIAL_ANN

#: The experiment's step, as classify_materials_ann takes it by default.
STEP = inspect.signature(classify_materials_ann).parameters["learning_rate_init"].default


def _median_ms(function, repeats: int) -> float:
    """Median wall time of ``function()`` over ``repeats`` calls, ms."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return 1e3 * float(np.median(times))


def epoch_products(X, Y, W1, b1, W2, b2):
    """One epoch's arithmetic as a function of no arguments, its outputs allocated once: the
    forward pass (tanh, then the softmax), the error at the outputs and the backward pass to
    the two weight gradients, which it returns summed over the rows (``(G1, G2)``; the mean
    loss's are these over the number of rows)."""
    Z = np.empty((X.shape[0], W1.shape[1]))
    P = np.empty((X.shape[0], W2.shape[1]))
    G1, G2 = np.empty_like(W1), np.empty_like(W2)

    def epoch():
        np.matmul(X, W1, out=Z)
        np.tanh(np.add(Z, b1, out=Z), out=Z)
        np.add(np.matmul(Z, W2, out=P), b2, out=P)
        np.subtract(P, P.max(axis=1, keepdims=True), out=P)
        np.exp(P, out=P)
        np.divide(P, P.sum(axis=1, keepdims=True), out=P)
        np.subtract(P, Y, out=P)  # the softmax cross-entropy's error at the outputs
        np.matmul(Z.T, P, out=G2)
        D = np.matmul(P, W2.T)
        D *= 1.0 - Z * Z
        np.matmul(X.T, D, out=G1)
        return G1, G2

    return epoch


def measure(rows: int, features: int, hidden: int, classes: int, repeats: int, seed: int = 0):
    """``{"epoch": ms, "validation": ms, "products": ms}`` on random data of these shapes (the
    validation rows: 15 % of ``rows``, as the paper's split), BLAS on one thread as the study's
    steps run it."""
    rng = np.random.default_rng(seed)
    X = rng.random((rows, features))
    labels = np.array([f"m{k}" for k in range(classes)])
    y = labels[rng.integers(0, classes, rows)]
    y[:classes] = labels  # every class present
    X_val = rng.random((max(1, round(0.15 * rows)), features))
    with limited_threads(1), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # one epoch per call: its iteration limit, on purpose
        model = MLPClassifier(hidden_layer_sizes=(hidden,), activation="tanh", solver="gd",
                              learning_rate_init=STEP, max_iter=1,
                              random_state=seed, warm_start=True, alpha=0.0)
        model.fit(X, y)  # the weights drawn; later calls continue them
        Y = (y[:, None] == model.classes_).astype(float)
        (W1, W2), (b1, b2) = model.coefs_, model.intercepts_
        return {
            "epoch": _median_ms(lambda: model.fit(X, y), repeats),
            "validation": _median_ms(lambda: model.predict_log_proba(X_val), repeats),
            "products": _median_ms(epoch_products(X, Y, W1, b1, W2, b2), repeats),
        }


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rows", type=int, default=6913,
                        help="training rows (default: the paper data set's 70 %%)")
    parser.add_argument("--features", type=int, default=256, help="inputs (default 256)")
    parser.add_argument("--hidden", type=int, default=MATERIAL_ANN.hidden_layer_sizes[0],
                        help="hidden tanh units (default: the paper's)")
    parser.add_argument("--classes", type=int, default=5, help="materials (default 5)")
    parser.add_argument("--repeats", type=int, default=50, help="epochs timed (>= 1)")
    parser.add_argument("--epochs", type=int, default=1000,
                        help="epochs of a run, to scale the totals (default 1000)")
    args = parser.parse_args(argv)
    for name in ("rows", "features", "hidden", "repeats", "epochs"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be >= 1, got {getattr(args, name)}")
    if not 2 <= args.classes <= args.rows:
        parser.error(f"--classes must be from 2 to --rows, got {args.classes}")
    ms = measure(args.rows, args.features, args.hidden, args.classes, args.repeats)
    run = ms["epoch"] + ms["validation"]
    print(f"{args.rows} rows x {args.features} features, {args.hidden} tanh units, "
          f"{args.classes} classes; median of {args.repeats} epochs, BLAS on one thread")
    print(f"{'part':<40}{'ms / epoch':>12}{f's / {args.epochs} epochs':>20}")
    for label, value in (("epoch (MLPClassifier.fit, warm start)", ms["epoch"]),
                         ("validation pass (predict_log_proba)", ms["validation"]),
                         ("the epoch's products alone (floor)", ms["products"])):
        print(f"{label:<40}{value:>12.2f}{value * args.epochs / 1e3:>20.1f}")
    # a run at the floor still makes its validation pass (taken as measured) and its updates
    # (four axpy, not timed): the floor's share of the run is a lower bound
    floor = ms["products"] + ms["validation"]
    print(f"the estimator's share of an epoch: {1 - ms['products'] / ms['epoch']:.0%}; a run "
          f"with its epochs at the floor (the validation pass as measured, the weight updates "
          f"not counted) takes at least {floor / run:.2f} of the time")


if __name__ == "__main__":
    main()
