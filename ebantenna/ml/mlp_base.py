"""The machinery shared by the two multilayer perceptrons of :mod:`ebantenna.ml.mlp`.

:class:`BaseMLP` holds scikit-learn's parameters and their constraints (validated by
scikit-learn's ``_fit_context``), the declared fitted attributes, and the training loops: epochs
of the first-order solvers with their optimisers of :mod:`ebantenna.ml.optimizers`, Møller's SCG,
L-BFGS through SciPy, and early stopping.

Every solver evaluates the loss and its gradient with the training engine (a private module that
reuses its arrays from batch to batch), which the tests hold equal, bit for bit, to the
reference :mod:`ebantenna.ml.backprop`; :meth:`BaseMLP.loss_and_gradient` evaluates the
reference itself. The public methods of the estimators validate their input once; the training
steps below them take checked values.
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
from sklearn.utils import check_random_state
from sklearn.utils._param_validation import Interval, Options, StrOptions
from sklearn.utils.validation import check_is_fitted

from .._budget import check_allocation
from .._engines import interrupts_pass_through
from .._validate import (
    check_bool,
    check_choice,
    check_in_range,
    check_positive,
    check_python_number,
    check_real,
    describe,
)
from ._backprop_engine import Workspace, loss_and_gradients_into
from ._mlp_compiled import compiled_kernels
from ._mlp_optimizers import InPlaceAdam, InPlaceMomentum
from .backprop import ACTIVATIONS, glorot_uniform, loss_and_gradients, pack, train_epochs, unpack
from .fitted import INPUT_ATTRIBUTES, FittedAttribute
from .optimizers import Adam, Momentum, scg_init, scg_step

__all__ = ["BaseMLP", "ACTIVATIONS", "SOLVERS", "training_optimizer"]

logger = logging.getLogger(__name__)

#: Training algorithms.
SOLVERS = ("gd", "sgd", "adam", "scg", "lbfgs")


def training_optimizer(name: str, params, learning_rate: float = 1e-3, *, momentum: float = 0.9,
                       nesterov: bool = True, beta_1: float = 0.9, beta_2: float = 0.999,
                       epsilon: float = 1e-8, engine: str = "auto"):
    """The optimiser the estimators train with, made for the arrays ``params``.

    ``engine="reference"`` gives the textbook classes of :mod:`ebantenna.ml.optimizers`;
    ``"auto"`` their engine, which runs the same operations in place on temporaries allocated
    once, and Adam's as one compiled loop per array when numba is installed (the same bits).

    Parameters
    ----------
    name : {'adam', 'momentum'}
        :class:`~ebantenna.ml.optimizers.Adam` or :class:`~ebantenna.ml.optimizers.Momentum`.
    params : list of ndarray
        The arrays the optimiser will move.
    learning_rate, momentum, nesterov, beta_1, beta_2, epsilon
        As for those classes (``momentum`` and ``nesterov`` for 'momentum', the others for
        'adam').
    engine : {'auto', 'reference'}

    Examples
    --------
    >>> p = [np.array([1.0])]
    >>> opt = training_optimizer("adam", p, 0.1, engine="reference")
    >>> type(opt).__name__
    'Adam'
    >>> opt.update(p, [np.array([3.0])]); np.round(p[0], 6)
    array([0.9])
    """
    check_choice("name", name, ("adam", "momentum"))
    check_choice("engine", engine, ("auto", "reference"))
    if not isinstance(params, list | tuple) or not all(
            isinstance(p, np.ndarray) and p.dtype.kind == "f" for p in params):
        raise TypeError(f"params must be a list of float ndarrays (the arrays to move), got "
                        f"{type(params).__name__}")
    learning_rate = check_positive("learning_rate", learning_rate)
    momentum = check_in_range("momentum", momentum, 0.0, 1.0, low_inclusive=True,
                              high_inclusive=True)
    nesterov = check_bool("nesterov", nesterov)
    beta_1 = check_in_range("beta_1", beta_1, 0.0, 1.0, low_inclusive=True)
    beta_2 = check_in_range("beta_2", beta_2, 0.0, 1.0, low_inclusive=True)
    epsilon = check_positive("epsilon", epsilon)
    reference = engine == "reference"
    if name == "adam":
        args = (params, learning_rate, beta_1, beta_2, epsilon)
        return Adam(*args) if reference else InPlaceAdam(*args, compiled=compiled_kernels())
    args = (params, learning_rate, momentum, nesterov)
    return Momentum(*args) if reference else InPlaceMomentum(*args)


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
        "engine": [StrOptions({"auto", "reference"})],
    }

    #: Attributes that ``fit`` sets on every network (see :mod:`ebantenna.ml.fitted`).
    _fitted_schema = (
        FittedAttribute("coefs_", "arrays", dtype="float64", ndim=2),
        FittedAttribute("intercepts_", "arrays", dtype="float64", ndim=1),
        FittedAttribute("loss_curve_", "value"),
        # optional: files saved before it existed load without it
        FittedAttribute("loss_", "value", optional=True),
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
        # the count of epochs without progress, which warm_start continues as scikit-learn's
        # does: saved (optional: files written before it was kept load without it)
        FittedAttribute("_no_improvement", "value", optional=True),
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
        engine="auto",
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
        self.engine = engine

    #: The real-valued parameters; each must be a finite number (``n_iter_no_change`` may be inf).
    _REAL_PARAMETERS = ("alpha", "learning_rate_init", "power_t", "tol", "momentum",
                        "validation_fraction", "beta_1", "beta_2", "epsilon", "sigma0", "lambda0")

    def _validate_params(self):
        """Numbers scikit-learn's constraints cannot take (10**400, a Fraction) refused by name,
        then those constraints, with scikit-learn's errors."""
        for name in self._REAL_PARAMETERS:
            check_python_number(name, getattr(self, name))
        super()._validate_params()

    def _check_numbers(self) -> None:
        """Every real parameter finite, whatever its Python size (scikit-learn's constraints take
        ``alpha=10**400`` as a real number, and ``float()`` of it would overflow)."""
        for name in self._REAL_PARAMETERS:
            check_real(name, getattr(self, name))

    def _check_size(self, sizes: list[int], n_rows: int) -> None:
        """Refuse a network over the memory budget before its weights are drawn.

        The weights, and about five copies of them (gradients, the optimiser's state, the best
        network kept), plus the activations and their gradients for every row of a batch.
        """
        n_weights = sum((a + 1) * b for a, b in zip(sizes[:-1], sizes[1:], strict=False))
        check_allocation(8 * (6 * n_weights + 3 * n_rows * sum(sizes)),
                         parameter="hidden_layer_sizes",
                         what=f"a network of {describe(n_weights)} weights")

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

    def _loss_and_gradients_into(self, X, Y, coefs, intercepts, grads, work) -> float:
        """The training engine's loss, the gradients written into ``grads`` (two lists of arrays)
        and the intermediate arrays into ``work``, a ``Workspace`` of ``X``'s number of rows
        (:mod:`ebantenna.ml.backprop` holds the reference it equals); with ``engine='reference'``
        the reference's own loss and gradients (``work`` unused, may be None). The values are
        checked."""
        # Every solver checks that the loss is finite and stops with a clear error when it is
        # not; NumPy's overflow warnings on the way there would only be noise before it.
        with np.errstate(over="ignore", invalid="ignore"):
            if self.engine == "reference":  # the textbook's functions, the same numbers
                loss, coef_grads, intercept_grads = loss_and_gradients(
                    X, Y, coefs, intercepts, self.activation, self.out_activation_, self.alpha)
                for out, grad in zip((*grads[0], *grads[1]), (*coef_grads, *intercept_grads),
                                     strict=True):
                    out[...] = grad
                return loss
            return loss_and_gradients_into(X, Y, coefs, intercepts, self.activation,
                                           self.out_activation_, self.alpha, grads, work)

    def _full_batch_objective(self, X, Y):
        """``f(w) -> (loss, gradient)`` at flattened parameters ``w`` on the whole training set,
        for 'lbfgs' and 'scg' (each call returns a gradient array of its own)."""
        shapes = [c.shape for c in self.coefs_]
        work = (None if self.engine == "reference" else
                Workspace(X.shape[0], [X.shape[1], *(s[1] for s in shapes)], compiled_kernels()))
        grad = np.empty(sum(fan_in * fan_out + fan_out for fan_in, fan_out in shapes))
        grads = unpack(grad, shapes)

        def loss_and_flat_gradient(w):
            coefs, intercepts = unpack(w, shapes)
            loss = self._loss_and_gradients_into(X, Y, coefs, intercepts, grads, work)
            return loss, grad.copy()

        return loss_and_flat_gradient

    def loss_and_gradient(self, X, Y, w=None):
        """Loss and flattened gradient at the flattened parameters ``w`` (default: fitted ones),
        computed by the reference :func:`ebantenna.ml.backprop.loss_and_gradients`.

        ``Y`` is the encoded target (one-hot for classes, 2-D for regression), as used in
        training. Meant for checks such as finite differences. The network must be fitted, since
        the layer shapes come from ``coefs_``; to evaluate it at weights of your own, set
        ``coefs_`` and ``intercepts_`` yourself (and ``alpha=0`` for the bare loss), as exercise 7
        does, and pass your ``w`` (laid out as :func:`ebantenna.ml.backprop.pack` does).
        """
        check_is_fitted(self)
        shapes = [c.shape for c in self.coefs_]
        w = pack(self.coefs_, self.intercepts_) if w is None else np.asarray(w, float)
        coefs, intercepts = unpack(w, shapes)
        X = X if issparse(X) else np.asarray(X, float)
        with np.errstate(over="ignore", invalid="ignore"):  # a loss that is not finite says it
            loss, coef_grads, intercept_grads = loss_and_gradients(
                X, np.asarray(Y, float), coefs, intercepts, self.activation,
                self.out_activation_, self.alpha)
        return loss, pack(coef_grads, intercept_grads)

    # --------------------------------------------------------- training
    @interrupts_pass_through()  # a Ctrl-C inside a compiled loop stays a KeyboardInterrupt
    def _fit(self, X, Y, y_for_split, incremental=False):
        """Train on checked ``X`` and encoded ``Y``; with ``incremental`` (``partial_fit``) one
        epoch, continuing the optimiser's state (velocities, moments, learning rate, samples
        seen) from the previous call.

        The steps: build the network (or continue the fitted one), set a validation split aside
        for early stopping, run the solver, keep the best network seen on the validation split.
        One generator seeded by ``random_state`` draws, in this order, the initial weights and
        the shuffles of the epochs; the validation split is scikit-learn's (see
        :meth:`_split_random_state`).
        """
        self._check_numbers()
        sizes = [X.shape[1], *self._hidden_sizes(), Y.shape[1]]
        self._check_size(sizes, X.shape[0])
        if incremental and self.early_stopping:
            raise ValueError("partial_fit does not support early_stopping=True")
        rng = np.random.default_rng(self.random_state)
        fresh = not ((self.warm_start or incremental) and hasattr(self, "coefs_"))
        if fresh:
            self._initialize_network(sizes, rng)
        else:
            self._continue_network(sizes)
        # as scikit-learn: n_iter_ counts the epochs of this call (one for partial_fit)
        self.n_iter_ = 0
        self.n_layers_ = len(sizes)
        self.n_outputs_ = Y.shape[1]
        X_val = Y_val = None
        if self.early_stopping and self.solver != "lbfgs":  # as scikit-learn: ignored by lbfgs
            X, Y, X_val, Y_val = self._validation_split(X, Y, rng, sizes, fresh)
        # as scikit-learn, the count of epochs without progress carries on with warm_start
        if fresh or not hasattr(self, "_no_improvement"):
            self._no_improvement = 0
        if self.solver == "lbfgs":
            self._train_lbfgs(X, Y)
        elif self.solver == "scg":
            self._train_scg(X, Y, X_val, Y_val)
        else:
            self._train_first_order(X, Y, X_val, Y_val, rng, incremental)
        self._keep_best(incremental)
        return self

    def _initialize_network(self, sizes, rng) -> None:
        """Glorot-uniform weights for layers of the given ``sizes`` and an empty history."""
        self.coefs_, self.intercepts_ = glorot_uniform(sizes, self.activation, rng)
        self.loss_curve_ = []
        self.t_ = 0
        self.best_loss_ = np.inf
        self.validation_scores_ = None
        self.best_validation_score_ = None

    def _continue_network(self, sizes) -> None:
        """Continue from the fitted weights (``warm_start``, ``partial_fit``): they must fit
        layers of the given ``sizes``; the history carries on."""
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

    def _split_random_state(self, rng, sizes, fresh):
        """What draws the validation split: the ``RandomState`` that scikit-learn's
        ``_fit_stochastic`` hands to ``train_test_split`` for the same ``random_state``.

        scikit-learn makes it with ``check_random_state(random_state)`` at every ``fit`` and,
        on a fresh network, first draws the initial weights from it (a ``uniform`` array of each
        layer's weights, then of its biases); those draws are repeated here, so that the split
        is the same. A ``RandomState`` instance is used as it is: it has given this network its
        initial weights already (through :func:`numpy.random.default_rng`, the same number of
        draws). A ``Generator``, ``SeedSequence`` or ``BitGenerator``, which scikit-learn does
        not take, gives a seed from ``rng``.
        """
        rs = self.random_state
        if isinstance(rs, np.random.RandomState):
            return rs
        if rs is None or isinstance(rs, Integral):
            state = check_random_state(rs)
            if fresh:
                for fan_in, fan_out in zip(sizes[:-1], sizes[1:], strict=True):
                    state.uniform(size=(fan_in, fan_out))
                    state.uniform(size=fan_out)
            return state
        return int(rng.integers(2**31 - 1))

    def _validation_split(self, X, Y, rng, sizes, fresh):
        """``X, Y, X_val, Y_val``: ``validation_fraction`` of the samples set aside for early
        stopping, the same samples as scikit-learn's for the same ``random_state``: stratified
        by class for a single output column (two classes) as there, not for more columns.
        A fresh network starts an empty score history; with ``warm_start`` the history and
        ``best_validation_score_`` carry on, as in scikit-learn."""
        state = self._split_random_state(rng, sizes, fresh)
        stratify = Y if isinstance(self, ClassifierMixin) and Y.shape[1] == 1 else None
        try:
            X, X_val, Y, Y_val = train_test_split(
                X, Y, test_size=self.validation_fraction, random_state=state, stratify=stratify)
        except ValueError as e:  # a class too small to stratify: raised, as scikit-learn does
            raise ValueError(f"early_stopping: the validation split cannot hold both classes "
                             f"in proportion ({e})") from e
        if X.shape[0] < 1 or X_val.shape[0] < 1:
            raise ValueError("early_stopping needs at least one training and one "
                             "validation sample")
        if fresh or getattr(self, "validation_scores_", None) is None:
            self.validation_scores_ = []
            self.best_validation_score_ = -np.inf
        self._best = None
        return X, Y, X_val, Y_val

    def _keep_best(self, incremental) -> None:
        """After training: the best network on the validation split (early stopping); the
        optimiser's state kept for the next ``partial_fit`` only."""
        best = getattr(self, "_best", None)
        if self.early_stopping and best is not None:
            self.coefs_, self.intercepts_ = best
        if hasattr(self, "_best"):
            del self._best
        if self.solver != "lbfgs":  # as scikit-learn: the mean loss of the last epoch
            self.loss_ = self.loss_curve_[-1] if self.loss_curve_ else None
        if not incremental and hasattr(self, "_optimizer"):
            # only partial_fit carries the optimiser to its next call (see partial_fit)
            del self._optimizer

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
        """Epochs of mini-batch steps of 'gd', 'sgd' or 'adam' (one epoch for ``partial_fit``),
        until the loss (or the validation score) stops improving or ``max_iter``: the reference
        loop :func:`~ebantenna.ml.backprop.train_epochs` with ``engine='reference'``, else the
        engine's loop, which does the same arithmetic in arrays allocated once."""
        n = X.shape[0]
        batch = n if self.solver == "gd" else min(
            200 if self.batch_size == "auto" else int(self.batch_size), n)
        shuffle = rng if self.shuffle and self.solver != "gd" else None
        stopped = [incremental]  # one epoch, no convergence to report

        def end_of_epoch(loss):
            self.t_ += n
            stopped[0] = self._stop_after_epoch(loss, X_val, Y_val, opt) or stopped[0]
            return stopped[0] and not incremental

        n_epochs = 1 if incremental else self.max_iter
        if self.engine == "reference":
            opt = self._first_order_optimizer([*self.coefs_, *self.intercepts_], incremental)
            # Every solver stops with a clear error on a loss that is not finite; NumPy's
            # overflow warnings on the way there would only be noise before it.
            with np.errstate(over="ignore", invalid="ignore"):
                train_epochs(X, Y, self.coefs_, self.intercepts_, opt,
                             activation=self.activation, out_activation=self.out_activation_,
                             alpha=self.alpha, batch_size=batch, n_epochs=n_epochs, rng=shuffle,
                             end_of_epoch=end_of_epoch)
        else:
            # one flat vector holds every weight and bias (coefs_ and intercepts_ are views of
            # it): the optimiser then moves all of them with a handful of NumPy calls per batch
            shapes = [c.shape for c in self.coefs_]
            w = pack(self.coefs_, self.intercepts_)
            self.coefs_, self.intercepts_ = unpack(w, shapes)
            grad = np.empty_like(w)
            opt = self._first_order_optimizer([w], incremental)
            step = self._mini_batch_step(X.shape[1], w, grad, opt)
            order = np.arange(n)
            for _ in range(n_epochs):
                if shuffle is not None:
                    shuffle.shuffle(order)
                if end_of_epoch(self._epoch(X, Y, order, batch, step)):
                    break
            # own arrays again, not views of the flat training vector
            self.coefs_ = [c.copy() for c in self.coefs_]
            self.intercepts_ = [b.copy() for b in self.intercepts_]
        if not stopped[0]:
            warnings.warn(f"{self.solver}: maximum iterations ({self.max_iter}) reached and the "
                          "optimization hasn't converged yet.", ConvergenceWarning, stacklevel=3)

    def _first_order_optimizer(self, params, incremental):
        """Adam or momentum (none for 'gd') on ``params`` (:func:`training_optimizer`);
        ``partial_fit`` continues the optimiser of the previous ``partial_fit``."""
        opt = getattr(self, "_optimizer", None) if incremental else None
        reference = self.engine == "reference"
        if opt is not None and isinstance(opt, (InPlaceAdam, InPlaceMomentum)) == reference:
            raise ValueError("engine changed between partial_fit calls: the optimiser's state "
                             "of one engine cannot continue on the other; call fit first")
        if opt is None:
            momentum = 0.0 if self.solver == "gd" else float(self.momentum)
            opt = training_optimizer(
                "adam" if self.solver == "adam" else "momentum", params,
                float(self.learning_rate_init), momentum=momentum,
                nesterov=bool(self.nesterovs_momentum) and momentum > 0, beta_1=self.beta_1,
                beta_2=self.beta_2, epsilon=self.epsilon, engine=self.engine)
        self._optimizer = opt
        return opt

    def _mini_batch_step(self, n_features, w, grad, opt):
        """``step(Xb, Yb) -> loss``: the loss and gradient of one mini-batch by the engine, then
        the optimiser's move of ``w`` (of which ``coefs_`` and ``intercepts_`` are views)."""
        grads = unpack(grad, [c.shape for c in self.coefs_])  # the gradient's layers
        sizes = [n_features, *(W.shape[1] for W in self.coefs_)]
        # the arrays of one batch's forward and backward pass, reused by every batch of the same
        # size (two sizes at most: the full batches and the last, shorter one)
        workspaces = {}
        compiled = compiled_kernels()

        def step(Xb, Yb):
            rows = Xb.shape[0]
            if rows not in workspaces:
                workspaces[rows] = Workspace(rows, sizes, compiled)
            loss = self._loss_and_gradients_into(Xb, Yb, self.coefs_, self.intercepts_, grads,
                                                 workspaces[rows])
            opt.update([w], [grad])
            return loss

        return step

    def _epoch(self, X, Y, order, batch, step) -> float:
        """One pass over the mini-batches of ``X`` in the given ``order``; the mean loss."""
        n = X.shape[0]
        total = 0.0
        for start in range(0, n, batch):
            # a batch-sized copy stays in cache; one shuffled copy of X per epoch is slower.
            # Y.take, not Y[rows]: for a narrow array such as the one-hot targets, NumPy's
            # fancy indexing costs three times as much as take (the same rows either way).
            rows = order[start : start + batch]
            Xb, Yb = (X, Y) if batch >= n else (X[rows], Y.take(rows, axis=0))
            total += step(Xb, Yb) * Xb.shape[0]
        return total / n

    def _stop_after_epoch(self, loss, X_val, Y_val, opt) -> bool:
        """Record the epoch, apply the learning-rate schedule; True when training stops."""
        if not np.isfinite(loss):
            raise ValueError("the loss is not finite: lower learning_rate_init or scale "
                             "the features")
        if self.learning_rate == "invscaling" and self.solver != "adam":
            # scikit-learn's schedule: once per epoch, by the number of samples seen
            opt.learning_rate = self.learning_rate_init / (self.t_ + 1) ** self.power_t
        if not self._end_of_epoch(loss, X_val, Y_val):
            return False
        if (self.learning_rate == "adaptive" and self.solver != "adam"
                and opt.learning_rate > 1e-6):
            opt.learning_rate /= 5.0
            self._no_improvement = 0
            return False
        return True

    def _train_lbfgs(self, X, Y):
        """scikit-learn's 'lbfgs': :func:`scipy.optimize.minimize` with L-BFGS-B on the full
        batch, ``maxiter=max_iter``, ``maxfun=max_fun``, ``gtol=tol``. ``loss_curve_`` holds the
        loss after each iteration (scikit-learn keeps none for this solver)."""
        shapes = [c.shape for c in self.coefs_]
        objective = self._full_batch_objective(X, Y)
        last = {}

        def fg(w):
            loss, grad = objective(w)
            last["w"], last["f"] = w.copy(), loss
            return loss, grad

        def record(w):  # the iterate is normally the point evaluated last
            f = last["f"] if np.array_equal(w, last["w"]) else fg(w)[0]
            self.loss_curve_.append(float(f))
            self.best_loss_ = min(self.best_loss_, float(f))

        res = optimize.minimize(fg, pack(self.coefs_, self.intercepts_), jac=True,
                                method="L-BFGS-B", callback=record,
                                options={"maxfun": int(self.max_fun),
                                         "maxiter": int(self.max_iter), "gtol": float(self.tol)})
        if not np.isfinite(res.fun):
            raise ValueError("lbfgs: the loss is not finite: scale the features and targets")
        self.coefs_, self.intercepts_ = unpack(res.x, shapes)
        self.loss_ = float(res.fun)  # as scikit-learn: the loss at the final weights
        self.n_iter_ = min(int(res.nit), int(self.max_iter))
        self.t_ += X.shape[0] * self.n_iter_
        if res.status != 0:
            message = res.message.decode() if isinstance(res.message, bytes) else res.message
            warnings.warn(f"lbfgs failed to converge after {res.nit} iteration(s) "
                          f"(status={res.status}): {message}", ConvergenceWarning, stacklevel=3)

    def _train_scg(self, X, Y, X_val, Y_val):
        """Netlab's scaled conjugate gradient on the full batch (see
        :func:`ebantenna.ml.optimizers.scg_step`), until the loss (or the validation score) stops
        improving, the gradient vanishes, or ``max_iter``."""
        shapes = [c.shape for c in self.coefs_]
        fg = self._full_batch_objective(X, Y)
        state = scg_init(pack(self.coefs_, self.intercepts_), fg, lambda0=float(self.lambda0))
        stopped = False
        for _ in range(self.max_iter):
            f_before = state.f
            scg_step(state, fg, sigma0=float(self.sigma0))
            self.coefs_, self.intercepts_ = unpack(state.w.copy(), shapes)
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
