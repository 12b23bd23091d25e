"""
Training a network: gradient descent against scaled conjugate gradients
=======================================================================

The paper trains its material classifier by gradient descent and its best distance regressor by
scaled conjugate gradients (MATLAB's ``trainscg``). :class:`ebantenna.ml.MLPRegressor
<ebantenna.ml.mlp.MLPRegressor>` has both (``solver="gd"`` and ``solver="scg"``). Here a small
network learns a smooth curve, a stand-in for "dominant frequency -> contact distance", and the two
loss curves are compared.
"""

import warnings

import matplotlib.pyplot as plt
import numpy as np
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import MLPRegressor

rng = np.random.default_rng(1)
X = rng.uniform(-1, 1, size=(200, 1))
y = np.sin(2.5 * X[:, 0]) + 0.05 * rng.standard_normal(200)

common = dict(hidden_layer_sizes=(9,), activation="tanh", max_iter=300, random_state=0, tol=0.0,
              n_iter_no_change=300)
# Both run the same fixed number of epochs (tol=0), so each warns that it stopped at max_iter:
# that is intended here.
with warnings.catch_warnings():
    warnings.simplefilter("ignore", ConvergenceWarning)
    gd = MLPRegressor(solver="gd", learning_rate_init=0.2, **common).fit(X, y)
    scg = MLPRegressor(solver="scg", **common).fit(X, y)
for name, model in (("gd", gd), ("scg", scg)):
    print(f"{name:3s}: {model.n_iter_} epochs, final loss {model.loss_curve_[-1]:.2e}, "
          f"R^2 {model.score(X, y):.3f}")

fig, ax1 = plt.subplots(figsize=(6.5, 4))
ax1.semilogy(gd.loss_curve_, label="gradient descent")
ax1.semilogy(scg.loss_curve_, label="scaled conjugate gradient")
ax1.set_xlabel("epoch (one SCG epoch evaluates the gradient up to twice)")
ax1.set_ylabel("training loss (half mean squared error)")
ax1.legend()
fig.tight_layout()

# %%
# What each network has learnt after its 300 epochs: the fitted curves over the data.
fig, ax2 = plt.subplots(figsize=(6.5, 4))
xs = np.linspace(-1, 1, 200)[:, None]
ax2.plot(X[:, 0], y, ".", color="0.6", ms=3, label="data")
ax2.plot(xs[:, 0], gd.predict(xs), label="gd")
ax2.plot(xs[:, 0], scg.predict(xs), label="scg")
ax2.set_xlabel("input x")
ax2.set_ylabel("target y = sin(2.5 x) + noise")
ax2.legend()
fig.tight_layout()
plt.show()
