"""The machinery shared by the two multilayer perceptrons of :mod:`ebantenna.ml.mlp`.

:class:`BaseMLP` holds scikit-learn's parameters and their constraints (validated by
scikit-learn's ``_fit_context``), the declared fitted attributes, the loss and gradient built from
:mod:`ebantenna.ml.backprop`, and the training loops: epochs of the first-order solvers with
their optimisers of :mod:`ebantenna.ml.optimizers`, Møller's SCG, and early stopping.
"""

from __future__ import annotations

import logging
import warnings
from numbers import Integral, Real

import numpy as np
from scipy import optimize
from scipy.sparse import issparse
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.exceptions import ConvergenceWarning
from sklearn.model_selection import train_test_split
from sklearn.utils._param_validation import Interval, Options, StrOptions
from sklearn.utils.validation import check_is_fitted

from .backprop import (
    ACTIVATIONS,
    Workspace,
    backprop,
    forward,
    glorot_uniform,
    output_loss,
    pack,
    unpack,
)
from .fitted import INPUT_ATTRIBUTES, FittedAttribute
from .optimizers import Adam, Momentum, scg_init, scg_step

__all__ = ["BaseMLP", "ACTIVATIONS", "SOLVERS"]

logger = logging.getLogger(__name__)

#: Training algorithms.
SOLVERS = ("gd", "sgd", "adam", "scg", "lbfgs")


class BaseMLP(BaseEstimator):
    """Base of :class:`~ebantenna.ml.mlp.MLPClassifier` and :class:`~ebantenna.ml.mlp.MLPRegressor`:
    parameters, their constraints, the fitted schema and the training loops.

    Not meant to be used on its own: the subclasses add the output layer and the targets.
    """

    # scikit-learn's constraints and wording, with this package's solvers; validation_fraction
    # excludes 0, which would leave an empty validation split
    _parameter_constraints: dict = {
        "hidden_layer_sizes": ["array-like", Interval(Integral, 1, None, closed="left")],
        "activation": [StrOptions({"identity", "logistic", "tanh", "relu"})],
        "solver": [StrOptions({"gd", "sgd", "adam", "scg", "lbfgs"})],
        "alpha": [Interval(Real, 0, None, closed="left")],
        "batch_size": [StrOptions({"auto"}), Interval(Integral, 1, None, closed="left")],
        "learning_rate": [StrOptions({"constant", "invscaling", "adaptive"})],
        "learning_rate_init": [Interval(Real, 0, None, closed="neither")],
        "power_t": [Interval(Real, 0, None, closed="left")],
        "max_iter": [Interval(Integral, 1, None, closed="left")],
        "shuffle": ["boolean"],
        "random_state": [None, Interval(Integral, 0, None, closed="left"),
                         np.random.RandomState, np.random.Generator, np.random.SeedSequence,
                         np.random.BitGenerator],
        "tol": [Interval(Real, 0, None, closed="left")],
        "verbose": ["verbose"],
        "warm_start": ["boolean"],
        "momentum": [Interval(Real, 0, 1, closed="both")],
        "nesterovs_momentum": ["boolean"],
        "early_stopping": ["boolean"],
        "validation_fraction": [Interval(Real, 0, 1, closed="neither")],
        "beta_1": [Interval(Real, 0, 1, closed="left")],
        "beta_2": [Interval(Real, 0, 1, closed="left")],
        "epsilon": [Interval(Real, 0, None, closed="neither")],
        "n_iter_no_change": [Interval(Integral, 1, None, closed="left"), Options(Real, {np.inf})],
        "sigma0": [Interval(Real, 0, None, closed="neither")],
        "lambda0": [Interval(Real, 0, None, closed="neither")],
        "max_fun": [Interval(Integral, 1, None, closed="left")],
    }

    #: Attributes that ``fit`` sets on every network (see :mod:`ebantenna.ml.fitted`).
    _fitted_schema = (
        FittedAttribute("coefs_", "arrays", dtype="float64", ndim=2),
        FittedAttribute("intercepts_", "arrays", dtype="float64", ndim=1),
        FittedAttribute("loss_curve_", "value"),
        FittedAttribute("n_iter_", "value"),
        FittedAttribute("t_", "value"),
        FittedAttribute("best_loss_", "value"),
        FittedAttribute("validation_scores_", "value", since=2),
        FittedAttribute("best_validation_score_", "value", since=2),
        FittedAttribute("n_layers_", "value"),
        FittedAttribute("n_outputs_", "value"),
        # the optimiser's state, which partial_fit continues: not saved (a loaded network
        # continues with a fresh optimiser, its learning rate back at learning_rate_init)
        FittedAttribute("_optimizer", "rebuilt", optional=True),
        FittedAttribute("_no_improvement", "rebuilt", optional=True),
        *INPUT_ATTRIBUTES,
    )

    def __init__(
        self,
        hidden_layer_sizes=(100,),
        activation="relu",
        *,
        solver="adam",
        alpha=0.0001,
        batch_size="auto",
        learning_rate="constant",
        learning_rate_init=0.001,
        power_t=0.5,
        max_iter=200,
        shuffle=True,
        random_state=None,
        tol=1e-4,
        verbose=False,
        warm_start=False,
        momentum=0.9,
        nesterovs_momentum=True,
        early_stopping=False,
        validation_fraction=0.1,
        beta_1=0.9,
        beta_2=0.999,
        epsilon=1e-8,
        n_iter_no_change=10,
        sigma0=1e-4,
        lambda0=1.0,
        max_fun=15000,
    ):
        self.hidden_layer_sizes = hidden_layer_sizes
        self.activation = activation
        self.solver = solver
        self.alpha = alpha
        self.batch_size = batch_size
        self.learning_rate = learning_rate
        self.learning_rate_init = learning_rate_init
        self.power_t = power_t
        self.max_iter = max_iter
        self.shuffle = shuffle
        self.random_state = random_state
        self.tol = tol
        self.verbose = verbose
        self.warm_start = warm_start
        self.momentum = momentum
        self.nesterovs_momentum = nesterovs_momentum
        self.early_stopping = early_stopping
        self.validation_fraction = validation_fraction
        self.beta_1 = beta_1
        self.beta_2 = beta_2
        self.epsilon = epsilon
        self.n_iter_no_change = n_iter_no_change
        self.sigma0 = sigma0
        self.lambda0 = lambda0
        self.max_fun = max_fun

    # ------------------------------------------------------------ network
    def _hidden_sizes(self) -> list[int]:
        """``hidden_layer_sizes`` as a list (the constraints have checked int or array-like)."""
        sizes = self.hidden_layer_sizes
        sizes = [sizes] if isinstance(sizes, Integral) else list(sizes)
        if any(isinstance(s, bool) or not isinstance(s, Integral) for s in sizes):
            raise TypeError(f"hidden_layer_sizes must contain integers, got {sizes!r}.")
        if any(s <= 0 for s in sizes):
            raise ValueError(f"hidden_layer_sizes must be > 0, got {sizes}.")
        return [int(s) for s in sizes]

    def _loss_grad(self, X, Y, coefs, intercepts, out=None, work=None):
        """Loss (data term + L2) and its exact gradient with respect to every weight and bias
        (written into ``out``, two lists of arrays, when given; the intermediate arrays into the
        :class:`~ebantenna.ml.backprop.Workspace` ``work`` of ``X``'s number of rows, when
        given)."""
        n = X.shape[0]
        # Every solver checks that the loss is finite and stops with a clear error when it is
        # not; NumPy's overflow warnings on the way there would only be noise before it.
        with np.errstate(over="ignore", invalid="ignore"):
            acts = forward(X, coefs, intercepts, self.activation,
                           None if work is None else work.activations)
            # with a workspace the logits' array takes their gradient: nothing reads them after
            data_loss, delta = output_loss(self.out_activation_, acts[-1], Y,
                                           None if work is None else acts[-1])
            # einsum, not a BLAS dot: no thread start-up for a reduction this small
            l2 = sum(float(np.einsum("ij,ij->", W, W)) for W in coefs)
            loss = data_loss + 0.5 * self.alpha * l2 / n
            coef_grads, intercept_grads = backprop(
                acts, delta, coefs, self.activation, self.alpha / n, out, work
            )
        return loss, coef_grads, intercept_grads

    def _forward(self, X, coefs, intercepts):
        return forward(X, coefs, intercepts, self.activation)

    # Flattened parameters for SCG and for finite-difference checks.
    def _pack(self, coefs, intercepts) -> np.ndarray:
        return pack(coefs, intercepts)

    def _unpack(self, w, shapes):
        return unpack(w, shapes)

    def loss_and_gradient(self, X, Y, w=None):
        """Loss and flattened gradient at the flattened parameters ``w`` (default: fitted ones).

        ``Y`` is the encoded target (one-hot for classes, 2-D for regression), as used in
        training. Meant for checks such as finite differences. The network must be fitted, since
        the layer shapes come from ``coefs_``; to evaluate it at weights of your own, set
        ``coefs_`` and ``intercepts_`` yourself (and ``alpha=0`` for the bare loss), as exercise 7
        does, and pass your ``w``.
        """
        check_is_fitted(self)
        shapes = [c.shape for c in self.coefs_]
        w = self._pack(self.coefs_, self.intercepts_) if w is None else np.asarray(w, float)
        coefs, intercepts = self._unpack(w, shapes)
        X = X if issparse(X) else np.asarray(X, float)
        loss, cg, ig = self._loss_grad(X, np.asarray(Y, float), coefs,
                                       intercepts)
        return loss, self._pack(cg, ig)

    # --------------------------------------------------------- training
    def _fit(self, X, Y, y_for_split, incremental=False):
        """Train; with ``incremental`` (``partial_fit``) one epoch, continuing the optimiser's
        state (velocities, moments, learning rate, samples seen) from the previous call."""
        hidden = self._hidden_sizes()
        if incremental and self.solver not in ("gd", "sgd", "adam"):
            raise ValueError(f"partial_fit is only available for the first-order solvers 'gd', "
                             f"'sgd' and 'adam'; solver={self.solver!r} works on the full batch "
                             "until it converges.")
        if incremental and self.early_stopping:
            raise ValueError("partial_fit does not support early_stopping=True")
        n_features, n_out = X.shape[1], Y.shape[1]
        sizes = [n_features, *hidden, n_out]
        first_pass = not ((self.warm_start or incremental) and hasattr(self, "coefs_"))
        rng = np.random.default_rng(self.random_state)
        if first_pass:
            self.coefs_, self.intercepts_ = glorot_uniform(sizes, self.activation, rng)
            self.loss_curve_ = []
            self.n_iter_ = 0
            self.t_ = 0
            self.best_loss_ = np.inf
            self.validation_scores_ = None
            self.best_validation_score_ = None
        else:
            expected = [(a, b) for a, b in zip(sizes[:-1], sizes[1:], strict=True)]
            got = [c.shape for c in self.coefs_]
            if got != expected:
                raise ValueError(f"coefs_ shapes {got} do not match the network {expected}")
            self.coefs_ = [np.array(c, dtype=np.float64) for c in self.coefs_]
            self.intercepts_ = [np.array(b, dtype=np.float64) for b in self.intercepts_]
            for name in ("loss_curve_", "n_iter_", "t_", "best_loss_"):
                if not hasattr(self, name):
                    setattr(self, name, {"loss_curve_": [], "best_loss_": np.inf}.get(name, 0))
            self.loss_curve_ = list(self.loss_curve_)
        # as scikit-learn: n_iter_ counts the epochs of this call (one for partial_fit)
        self.n_iter_ = 0
        self.n_layers_ = len(sizes)
        self.n_outputs_ = n_out
        X_val = Y_val = None
        if self.early_stopping and self.solver != "lbfgs":  # as scikit-learn: ignored by lbfgs
            stratify = y_for_split if isinstance(self, ClassifierMixin) else None
            seed = int(rng.integers(2**31 - 1))
            try:
                X, X_val, Y, Y_val = train_test_split(
                    X, Y, test_size=self.validation_fraction, random_state=seed,
                    stratify=stratify)
            except ValueError:
                X, X_val, Y, Y_val = train_test_split(
                    X, Y, test_size=self.validation_fraction, random_state=seed)
            if X.shape[0] < 1 or X_val.shape[0] < 1:
                raise ValueError("early_stopping needs at least one training and one "
                                 "validation sample")
            self.validation_scores_ = []
            self.best_validation_score_ = -np.inf
            self._best = None
        if not incremental or not hasattr(self, "_no_improvement"):
            self._no_improvement = 0
        if self.solver == "lbfgs":
            self._train_lbfgs(X, Y)
        elif self.solver == "scg":
            self._train_scg(X, Y, X_val, Y_val)
        else:
            self._train_first_order(X, Y, X_val, Y_val, rng, incremental)
        if self.early_stopping and self._best is not None:
            self.coefs_, self.intercepts_ = self._best
        if hasattr(self, "_best"):
            del self._best
        if not incremental:
            # only partial_fit carries the optimiser to its next call (see partial_fit)
            for name in ("_optimizer", "_no_improvement"):
                if hasattr(self, name):
                    delattr(self, name)
        return self

    def _end_of_epoch(self, loss, X_val, Y_val) -> bool:
        """Record the epoch; return True when training should stop for lack of progress."""
        self.loss_curve_.append(float(loss))
        self.n_iter_ += 1
        if self.verbose:
            logger.info("Iteration %d, loss = %.8f", self.n_iter_, loss)
        if self.early_stopping:
            score = self._validation_score(X_val, Y_val)
            self.validation_scores_.append(score)
            if score < self.best_validation_score_ + self.tol:
                self._no_improvement += 1
            else:
                self._no_improvement = 0
            if score > self.best_validation_score_:
                self.best_validation_score_ = score
                self._best = ([c.copy() for c in self.coefs_],
                              [b.copy() for b in self.intercepts_])
        else:
            if loss > self.best_loss_ - self.tol:
                self._no_improvement += 1
            else:
                self._no_improvement = 0
        if loss < self.best_loss_:
            self.best_loss_ = float(loss)
        return self._no_improvement > self.n_iter_no_change

    def _train_first_order(self, X, Y, X_val, Y_val, rng, incremental=False):
        n = X.shape[0]
        # one flat vector holds every weight and bias (coefs_ and intercepts_ are views of it):
        # the optimiser then moves all of them with a handful of NumPy calls per batch
        shapes = [c.shape for c in self.coefs_]
        w = self._pack(self.coefs_, self.intercepts_)
        self.coefs_, self.intercepts_ = self._unpack(w, shapes)
        params, grad = [w], np.empty_like(w)
        grads = self._unpack(grad, shapes)  # the gradient's layers, views of grad
        if self.solver == "gd":
            batch = n
        elif self.batch_size == "auto":
            batch = min(200, n)
        else:
            batch = min(int(self.batch_size), n)
        lr = float(self.learning_rate_init)
        # partial_fit continues the optimiser of the previous partial_fit
        opt = getattr(self, "_optimizer", None) if incremental else None
        if opt is None and self.solver == "adam":
            opt = Adam(params, lr, self.beta_1, self.beta_2, self.epsilon)
        elif opt is None:
            mom = 0.0 if self.solver == "gd" else float(self.momentum)
            opt = Momentum(params, lr, mom, bool(self.nesterovs_momentum) and mom > 0)
        self._optimizer = opt
        idx = np.arange(n)
        # the arrays of one batch's forward and backward pass, reused by every batch of the same
        # size (two sizes at most: the full batches and the last, shorter one)
        sizes = [X.shape[1], *(W.shape[1] for W in self.coefs_)]
        workspaces = {}
        stopped = incremental  # one epoch, no convergence to report
        for _ in range(1 if incremental else self.max_iter):
            if self.shuffle and self.solver != "gd":
                rng.shuffle(idx)
            total = 0.0
            for start in range(0, n, batch):
                # a batch-sized copy stays in cache; one shuffled copy of X per epoch is slower.
                # Y.take, not Y[sl]: for a narrow array such as the one-hot targets, NumPy's
                # fancy indexing costs three times as much as take (the same rows either way).
                sl = idx[start : start + batch]
                Xb, Yb = (X, Y) if batch >= n else (X[sl], Y.take(sl, axis=0))
                rows = Xb.shape[0]
                if rows not in workspaces:
                    workspaces[rows] = Workspace(rows, sizes)
                loss, _, _ = self._loss_grad(Xb, Yb, self.coefs_, self.intercepts_, grads,
                                             workspaces[rows])
                total += loss * Xb.shape[0]
                opt.update(params, [grad])
                self.t_ += Xb.shape[0]
            loss = total / n
            if not np.isfinite(loss):
                raise ValueError("the loss is not finite: lower learning_rate_init or scale "
                                 "the features")
            if self.learning_rate == "invscaling" and self.solver != "adam":
                # scikit-learn's schedule: once per epoch, by the number of samples seen
                opt.learning_rate = self.learning_rate_init / (self.t_ + 1) ** self.power_t
            if self._end_of_epoch(loss, X_val, Y_val):
                if (self.learning_rate == "adaptive" and self.solver != "adam"
                        and opt.learning_rate > 1e-6):
                    opt.learning_rate /= 5.0
                    self._no_improvement = 0
                    continue
                stopped = True
                break
        # own arrays again, not views of the flat training vector
        self.coefs_ = [c.copy() for c in self.coefs_]
        self.intercepts_ = [b.copy() for b in self.intercepts_]
        if not stopped:
            warnings.warn(f"{self.solver}: maximum iterations ({self.max_iter}) reached and the "
                          "optimization hasn't converged yet.", ConvergenceWarning, stacklevel=3)

    def _train_lbfgs(self, X, Y):
        """scikit-learn's 'lbfgs': :func:`scipy.optimize.minimize` with L-BFGS-B on the full
        batch, ``maxiter=max_iter``, ``maxfun=max_fun``, ``gtol=tol``. ``loss_curve_`` holds the
        loss after each iteration (scikit-learn keeps none for this solver)."""
        shapes = [c.shape for c in self.coefs_]
        last = {}

        def fg(w):
            coefs, intercepts = self._unpack(w, shapes)
            loss, cg, ig = self._loss_grad(X, Y, coefs, intercepts)
            last["w"], last["f"] = w.copy(), loss
            return loss, self._pack(cg, ig)

        def record(w):  # the iterate is normally the point evaluated last
            f = last["f"] if np.array_equal(w, last["w"]) else fg(w)[0]
            self.loss_curve_.append(float(f))
            self.best_loss_ = min(self.best_loss_, float(f))

        res = optimize.minimize(fg, self._pack(self.coefs_, self.intercepts_), jac=True,
                                method="L-BFGS-B", callback=record,
                                options={"maxfun": int(self.max_fun),
                                         "maxiter": int(self.max_iter), "gtol": float(self.tol)})
        if not np.isfinite(res.fun):
            raise ValueError("lbfgs: the loss is not finite: scale the features and targets")
        self.coefs_, self.intercepts_ = self._unpack(res.x, shapes)
        self.n_iter_ = min(int(res.nit), int(self.max_iter))
        self.t_ += X.shape[0] * self.n_iter_
        if res.status != 0:
            message = res.message.decode() if isinstance(res.message, bytes) else res.message
            warnings.warn(f"lbfgs failed to converge after {res.nit} iteration(s) "
                          f"(status={res.status}): {message}", ConvergenceWarning, stacklevel=3)

    def _train_scg(self, X, Y, X_val, Y_val):
        shapes = [c.shape for c in self.coefs_]

        def fg(w):
            coefs, intercepts = self._unpack(w, shapes)
            loss, cg, ig = self._loss_grad(X, Y, coefs, intercepts)
            return loss, self._pack(cg, ig)

        state = scg_init(self._pack(self.coefs_, self.intercepts_), fg,
                         lambda0=float(self.lambda0))
        stopped = False
        for _ in range(self.max_iter):
            f_before = state.f
            scg_step(state, fg, sigma0=float(self.sigma0))
            self.coefs_, self.intercepts_ = self._unpack(state.w.copy(), shapes)
            # the loss recorded for an epoch is the one at its start, as for the other solvers
            if self._end_of_epoch(f_before, X_val, Y_val):
                stopped = True
                break
            if float(state.grad @ state.grad) < 1e-24:
                stopped = True
                break
        if not stopped:
            warnings.warn(f"scg: maximum iterations ({self.max_iter}) reached and the "
                          "optimization hasn't converged yet.", ConvergenceWarning, stacklevel=3)
