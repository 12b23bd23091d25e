"""Exercise 7: backpropagation by hand for a one-hidden-layer network, checked three ways."""

import numpy as np

from ebantenna.ml import MLPRegressor

# [data]
rng = np.random.default_rng(7)
n, n_in, n_hidden = 20, 3, 5
X = rng.standard_normal((n, n_in))
y = rng.standard_normal(n)
W1, b1 = rng.standard_normal((n_in, n_hidden)), rng.standard_normal(n_hidden)
W2, b2 = rng.standard_normal((n_hidden, 1)), rng.standard_normal(1)
# [/data]


def loss_and_grads(W1, b1, W2, b2):
    """Half the mean squared error of a tanh network, and its gradient by backpropagation."""
    h = np.tanh(X @ W1 + b1)  # forward
    out = h @ W2 + b2
    diff = out - y[:, None]
    loss = 0.5 * np.mean(diff**2)
    delta2 = diff / n  # backward: dL/d(out)
    gW2, gb2 = h.T @ delta2, delta2.sum(axis=0)
    delta1 = (delta2 @ W2.T) * (1 - h**2)  # tanh' = 1 - tanh^2
    gW1, gb1 = X.T @ delta1, delta1.sum(axis=0)
    return loss, [gW1, gb1, gW2, gb2]


params = [W1, b1, W2, b2]
loss, grads = loss_and_grads(*params)

# 1. Central finite differences, one parameter at a time.
eps = 1e-6
for p, g in zip(params, grads, strict=True):
    numeric = np.zeros_like(p)
    for idx in np.ndindex(p.shape):
        saved = p[idx]
        p[idx] = saved + eps
        up = loss_and_grads(*params)[0]
        p[idx] = saved - eps
        down = loss_and_grads(*params)[0]
        p[idx] = saved
        numeric[idx] = (up - down) / (2 * eps)
    # central differences are accurate to about eps^2 * f''' + rounding / eps ~ 1e-9 here
    assert np.allclose(g, numeric, rtol=1e-6, atol=1e-9), np.abs(g - numeric).max()

# 2. The package's network with the same weights (alpha=0: no L2 term), given as the fitted
#    attributes coefs_ and intercepts_; no training needed.
net = MLPRegressor((n_hidden,), activation="tanh", alpha=0.0)
net.coefs_, net.intercepts_ = [W1, W2], [b1, b2]
loss_pkg, grad_pkg = net.loss_and_gradient(X, y[:, None])  # the target as a column
assert np.isclose(loss_pkg, loss, rtol=1e-14)
assert np.allclose(grad_pkg, np.concatenate([g.ravel() for g in grads]), rtol=1e-12, atol=1e-15)

# 3. A gradient step lowers the loss (the gradient points uphill).
step = [p - 0.1 * g for p, g in zip(params, grads, strict=True)]
assert loss_and_grads(*step)[0] < loss

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"loss": loss, "loss_after_step": loss_and_grads(*step)[0]}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
SUMS = "the same formula summed in another order changes only the last few of 16 digits"
TOLERANCES = {"loss": ("rel", 1e-9, SUMS), "loss_after_step": ("rel", 1e-9, SUMS)}

print(f"ok: loss {loss:.6f}; backpropagation = finite differences = ebantenna's gradient")
