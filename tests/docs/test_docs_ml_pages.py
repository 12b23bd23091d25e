"""Claims of the machine-learning pages (theory/mlp, theory/svm, the glossary, plot_08) pinned."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np

DOCS = Path(__file__).resolve().parents[2] / "docs"


def _page_text(name: str) -> str:
    return " ".join((DOCS / name).read_text().split())  # one space between words, lines joined


def test_mlp_same_epochs_only_without_shuffling():
    # theory/mlp: from the same weights and split the two libraries take the same epochs with
    # shuffle=False; with shuffle=True ebantenna draws the orders from its own generator
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.neural_network import MLPClassifier as SklearnMLP

    from ebantenna.ml import MLPClassifier

    text = _page_text("theory/mlp.rst")
    assert "from the same weights and the same split and with ``shuffle=False``" in text.lower() \
        or "From the same weights and the same split and with ``shuffle=False``" in text
    assert "With the default ``shuffle=True`` they do not" in text
    rng = np.random.default_rng(0)
    X = rng.normal(size=(60, 4))
    y = (X[:, 0] + X[:, 1] > 0).astype(int)
    gaps = {}
    for shuffle in (False, True):
        common = dict(hidden_layer_sizes=(5,), solver="sgd", batch_size=10, shuffle=shuffle,
                      random_state=0)
        ours, theirs = MLPClassifier(**common), SklearnMLP(**common)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            for est in (ours, theirs):
                est.set_params(max_iter=1).fit(X, y)
            for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                            strict=True):
                b[...] = a
            for est in (ours, theirs):
                est.set_params(warm_start=True, max_iter=2).fit(X, y)
        gaps[shuffle] = max(np.abs(a - b).max() for a, b in zip(ours.coefs_, theirs.coefs_,
                                                                    strict=True))
    assert gaps[False] < 1e-12  # the same epochs, to rounding
    assert gaps[True] > 1e-6  # other orders, other weights after the first epoch


def test_scg_restarts_after_n_w_successful_steps():
    # theory/mlp: the restart comes after n_w successful steps, not every n_w steps
    import inspect

    from ebantenna.ml import optimizers

    assert "after every :math:`n_w` successful steps" in _page_text("theory/mlp.rst")
    source = inspect.getsource(optimizers.scg_step)
    assert "st.n_success += 1" in source and "if st.n_success == st.w.size:" in source


def test_svm_penalty_unit_with_the_linear_kernel():
    # glossary: with the linear kernel C carries 1/(feature unit)^2: features x10 and C/100 give
    # the same machine
    from sklearn.datasets import make_moons

    from ebantenna.ml import SVC

    text = _page_text("glossary.rst")
    assert "1 with a dimensionless kernel (RBF); 1/(feature unit)² with the linear kernel" in text
    assert "need a :math:`C` a hundred times smaller for the same machine" in text
    X, y = make_moons(n_samples=200, noise=0.25, random_state=0)
    tol = 1e-8
    a = SVC(kernel="linear", C=1.0, tol=tol).fit(X, y)
    b = SVC(kernel="linear", C=1.0 / 100, tol=tol).fit(10 * X, y)
    # the scaled problem is the same dual (Q and C both x1/100 after dividing alpha by 100); each
    # run stops within the stopping bound of the one optimum: |w - w*| <= sqrt(2 tol sum C), and
    # f moves by that times |x| plus 2 tol through the bias
    bound = 2 * np.sqrt(2 * tol * 1.0 * y.size) * (np.linalg.norm(X, axis=1).max() + 1) + 2 * tol
    assert np.abs(a.decision_function(X) - b.decision_function(10 * X)).max() <= bound
    same_c = SVC(kernel="linear", C=1.0, tol=tol).fit(10 * X, y)
    assert np.abs(a.decision_function(X) - same_c.decision_function(10 * X)).max() > 10 * bound


def test_iris_twins_taken_by_different_engines():
    # theory/svm: rows 101 and 142 of iris are the same point; the reference and the default take
    # 101, libsvm_compat=True takes 142, decision values a few 1e-4 apart
    from sklearn.datasets import load_iris
    from sklearn.preprocessing import StandardScaler

    from ebantenna.ml import SVC

    text = _page_text("theory/svm.rst")
    assert "rows 101 and 142 are the same point" in text
    assert "a few times :math:`10^{-4}` apart, the digits depending on the machine's BLAS" in text
    assert "on the tests' problems (distinct points) the same support set" in \
        _page_text("architecture.rst")
    X, y = load_iris(return_X_y=True)
    X = StandardScaler().fit_transform(X)
    assert np.array_equal(X[101], X[142])
    compat = SVC(libsvm_compat=True).fit(X, y)
    ref = SVC(solver="reference").fit(X, y)
    default = SVC().fit(X, y)
    assert 142 in compat.support_ and 101 not in compat.support_
    for m in (ref, default):
        assert 101 in m.support_ and 142 not in m.support_
    gap = np.abs(compat.decision_function(X) - ref.decision_function(X)).max()
    assert 1e-4 <= gap < 1e-3


def test_plot_08_states_what_holds():
    # plot_08: the same support vectors, dual coefficients within 0.01, decisions about tol apart;
    # libsvm_compat=True to rounding (the numbers are pinned in test_docs_claims too)
    from sklearn.datasets import make_moons
    from sklearn.svm import SVC as SklearnSVC

    from ebantenna.ml import SVC

    text = " ".join((DOCS / "examples" / "plot_08_svm_vs_sklearn.py").read_text().split())
    assert "dual coefficients that differ by less than 0.01" in text
    assert "must find the same" not in text
    X, y = make_moons(n_samples=200, noise=0.25, random_state=0)
    ours = SVC(C=1.0, gamma=2.0).fit(X, y)
    ref = SklearnSVC(C=1.0, gamma=2.0).fit(X, y)
    assert np.array_equal(np.sort(ours.support_), np.sort(ref.support_))
    assert 1e-4 < np.abs(ours.dual_coef_ - ref.dual_coef_).max() < 0.01
    compat = SVC(C=1.0, gamma=2.0, libsvm_compat=True).fit(X, y)
    assert np.abs(compat.dual_coef_ - ref.dual_coef_).max() < 1e-10


def test_iris80_counts_stated_with_the_design():
    # theory/svm: the design of the iris-80 measurement is stated, the counts are said to depend
    # on the BLAS kernel; the precomputed matrix takes the same updates as scikit-learn's
    from sklearn.datasets import load_iris
    from sklearn.svm import SVC as SklearnSVC

    from ebantenna.ml import SVC

    text = _page_text("theory/svm.rst")
    assert "On 100 random subsets of 80 rows of iris classes 1 and 2" in text
    assert "an equal count does not mean an equal path" in text
    assert "depends on the machine's arithmetic" in text
    X, y = load_iris(return_X_y=True)
    X, y = X[y > 0], y[y > 0]
    rng = np.random.default_rng(0)
    for _ in range(20):
        idx = rng.choice(y.size, 80, replace=False)
        K = X[idx] @ X[idx].T
        ours = SVC(kernel="precomputed", libsvm_compat=True).fit(K, y[idx])
        theirs = SklearnSVC(kernel="precomputed").fit(K, y[idx])
        assert ours.n_iter_[0] == theirs.n_iter_[0]
        assert np.abs(ours.decision_function(K) - theirs.decision_function(K)).max() < 1e-9


def _notation_symbols() -> set[str]:
    text = (DOCS / "glossary.rst").read_text()
    table = text.split("Symbols with more than one meaning", 1)[1].split("\nGlossary\n", 1)[0]
    return set(re.findall(r"   \* - (\S+)\n", table))


def test_the_notation_table_lists_the_ml_clashes():
    # glossary: the letters the ML pages use with two meanings are in the table; the kernel's
    # second point is x' on the SVM page and in the glossary, so y there is a label only
    symbols = _notation_symbols()
    assert {"y", "m", "L", "H", "d", "f", "A", "B", "e", "P"} <= symbols
    svm = (DOCS / "theory" / "svm.rst").read_text()
    assert r"x \cdot y" not in svm and r"x - y" not in svm
    assert r"k(x, y)" not in (DOCS / "glossary.rst").read_text()
    assert "and so is :math:`\\delta`" in _page_text("glossary.rst")
