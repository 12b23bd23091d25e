"""The input contract of the finite-element steps: assembly, supports, eigen-solves, substructures,
sweeps and plots.

Each step refuses a mesh that is not a mesh (a string, unsorted nodes), a body that is not a
``Probe``, ``Rod``, ``Supports`` or ``Substructure``, matrices of the wrong shape, a NaN shift and a
contact outside the probe, naming the parameter; good inputs are checked against a closed form,
the documented example, or the reference computation the fast path must equal.

Found by these rows and fixed: unsorted nodes assembled into matrices, ``AttributeError`` for
an integer probe, supports, substructure, result or zones, ``IndexError`` from element matrices
of the wrong shape, NumPy's broadcast message from matrices of the wrong size, SciPy's "array
must not contain infs or NaNs" for a NaN shift, and a batch of meshes built with contacts beyond
the tip.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna import Probe, fem  # noqa: E402
from ebantenna.fem import assembly as A  # noqa: E402
from ebantenna.fem import banded, coupled_sweep, coupling, plot, sweeps  # noqa: E402
from ebantenna.fem import modal as MO  # noqa: E402

NAN = math.nan
P = Probe()
NODES = A.beam_mesh(0.4, 0.2, 8)
SUP = fem.Supports(0.2)
K, M = A.assemble(NODES, P)


def _sub():
    return coupling.rod_substructure(fem.Rod("pvc"), n_elements=8)


def all_rows():
    a, m, c = "ebantenna.fem.assembly.", "ebantenna.fem.modal.", "ebantenna.fem.coupling."
    return [
        Row(a + "assemble", "nodes-str", lambda: A.assemble("x", P), ("nodes",)),
        Row(a + "assemble", "nodes-unsorted", lambda: A.assemble(NODES[::-1], P), ("nodes",)),
        Row(a + "assemble", "nodes-nan", lambda: A.assemble(NODES * NAN, P), ("nodes",)),
        Row(a + "assemble", "probe-int", lambda: A.assemble(NODES, 5), ("probe",)),
        Row(a + "assemble", "engine-unknown", lambda: A.assemble(NODES, P, engine="x"),
            ("engine",)),
        # the scatter engine and the textbook loop give one matrix, bit for bit
        Row(a + "assemble", "engine-equals-loop", lambda: (A.assemble(NODES, P)[0],
                                                           A.assemble(NODES, P, engine="loop")[0]),
            same=lambda r: np.array_equal(r[0], r[1])),
        Row(a + "assemble_elements", "shape-3x3",
            lambda: A.assemble_elements(np.ones((3, 3, 3))), ("element_matrices",)),
        Row(a + "assemble_elements", "shared-node-adds-up",
            lambda: A.assemble_elements(np.ones((2, 4, 4)))[2:4, 2:4],
            same=lambda r: r.tolist() == [[2.0, 2.0], [2.0, 2.0]]),
        Row(a + "free_dofs", "supports-int", lambda: A.free_dofs(NODES, 5), ("supports",)),
        Row(a + "free_dofs", "nodes-one", lambda: A.free_dofs([0.0], SUP), ("nodes",)),
        # clamped: v0 and theta0 fixed; a rigid contact at node 4 fixes v4 (DOF 8)
        Row(a + "free_dofs", "by-hand", lambda: A.free_dofs(NODES, SUP),
            same=lambda r: r.tolist() == [d for d in range(18) if d not in (0, 1, 8)]),
        Row(a + "apply_supports", "K-wrong-size",
            lambda: A.apply_supports(np.ones((3, 3)), M, NODES, P, SUP), ("K",)),
        Row(a + "apply_supports", "M-wrong-size",
            lambda: A.apply_supports(K, M[:-1, :-1], NODES, P, SUP), ("M",)),
        Row(a + "apply_supports", "probe-str", lambda: A.apply_supports(K, M, NODES, "p", SUP),
            ("probe",)),
        Row(m + "solve_modes", "n_modes-0", lambda: MO.solve_modes(K, M, 0, shift=1.0),
            ("n_modes",)),
        Row(m + "solve_modes", "solver-unknown",
            lambda: MO.solve_modes(K, M, 2, shift=1.0, solver="x"), ("solver",)),
        Row(m + "solve_modes", "M-other-shape",
            lambda: MO.solve_modes(K, M[:-1, :-1], 2, shift=1.0), ("M",)),
        Row(m + "solve_modes", "shift-nan", lambda: MO.solve_modes(K, M, 2, shift=NAN),
            ("shift",)),
        Row(m + "eigenvalue_shift", "beam-int", lambda: MO.eigenvalue_shift(5), ("beam",)),
        Row(m + "eigenvalue_shift", "by-hand", lambda: MO.eigenvalue_shift(P),
            same=lambda s: s == P.flexural_rigidity / (P.mass_per_length * P.length**4)),
        Row(m + "clip_eigenvalues", "lam-str", lambda: MO.clip_eigenvalues("x", 1.0), ("lam",)),
        Row(m + "clip_eigenvalues", "shift-nan", lambda: MO.clip_eigenvalues(np.ones(3), NAN),
            ("shift",)),
        # a rigid-body eigenvalue a rounding below zero is floored; one well below is refused
        Row(m + "clip_eigenvalues", "rounding-floored",
            lambda: MO.clip_eigenvalues(np.array([-1e-12, 4.0]), 1.0),
            same=lambda r: r.tolist() == [0.0, 4.0]),
        Row(m + "strain_energy", "u-short", lambda: MO.strain_energy(NODES, P, SUP, np.ones(3)),
            ("u",)),
        Row(c + "probe_substructure", "contact-beyond-tip",
            lambda: coupling.probe_substructure(P, 0.5), ("contact",)),
        Row(c + "probe_substructure", "n_elements-0",
            lambda: coupling.probe_substructure(P, 0.2, n_elements=0), ("n_elements",)),
        Row(c + "rod_substructure", "rod-int", lambda: coupling.rod_substructure(5), ("rod",)),
        Row(c + "rod_substructure", "n_elements-10**9",
            lambda: coupling.rod_substructure(fem.Rod("pvc"), n_elements=10**9), ("n_elements",)),
        Row(c + "craig_bampton", "sub-int", lambda: coupling.craig_bampton(5, 2), ("sub",)),
        Row(c + "craig_bampton", "n_modes-negative", lambda: coupling.craig_bampton(_sub(), -1),
            ("n_modes",)),
        Row(c + "craig_bampton", "n_modes-beyond-the-mesh",
            lambda: coupling.craig_bampton(_sub(), 1000), ("n_modes",)),
        Row(c + "Substructure.full", "x-short", lambda: _sub().full(np.ones(2)), ("shape",)),
        Row("ebantenna.fem.sweeps.dense_sweep", "probe-int",
            lambda: sweeps.dense_sweep(5, np.array([0.2]), SUP, 8, 2), ("probe",)),
        Row("ebantenna.fem.sweeps.dense_sweep", "supports-str",
            lambda: sweeps.dense_sweep(P, np.array([0.2]), "x", 8, 2), ("supports",)),
        # the batched solve equals the reference, one modal analysis per contact
        Row("ebantenna.fem.sweeps.dense_sweep", "equals-the-reference", lambda: (
            sweeps.dense_sweep(P, np.array([0.1, 0.25]), SUP, 16, 3),
            sweeps.reference_sweep(P, np.array([0.1, 0.25]), SUP, 16, 3)),
            same=lambda r: np.allclose(r[0], r[1], rtol=1e-10, atol=0)),
        Row("ebantenna.fem.sweeps.reference_sweep", "n_modes-0",
            lambda: sweeps.reference_sweep(P, np.array([0.2]), SUP, 8, 0), ("n_modes",)),
        Row("ebantenna.fem.sweeps.reference_sweep", "probe-none",
            lambda: sweeps.reference_sweep(None, np.array([0.2]), SUP, 8, 2), ("probe",)),
        Row("ebantenna.fem.banded.sweep_meshes", "contacts-beyond-tip",
            lambda: banded.sweep_meshes(0.4, np.array([0.5]), 8), ("contacts",)),
        Row("ebantenna.fem.banded.sweep_meshes", "contacts-nan",
            lambda: banded.sweep_meshes(0.4, np.array([NAN]), 8), ("contacts",)),
        Row("ebantenna.fem.banded.sweep_meshes", "length-0",
            lambda: banded.sweep_meshes(0.0, np.array([0.1]), 8), ("length",)),
        Row("ebantenna.fem.banded.sweep_meshes", "as-beam_mesh",
            lambda: banded.sweep_meshes(0.4, np.array([0.1, 0.3]), 4)[0],
            same=lambda r: np.allclose(r, [A.beam_mesh(0.4, 0.1, 4), A.beam_mesh(0.4, 0.3, 4)],
                                       rtol=0, atol=1e-16)),
        Row("ebantenna.fem.coupled_sweep.coupled_sweep", "rods-int",
            lambda: coupled_sweep.coupled_sweep(P, 5, [0.2], 1e5), ("rods",)),
        Row("ebantenna.fem.coupled_sweep.coupled_sweep", "rods-a-rod",
            lambda: coupled_sweep.coupled_sweep(P, fem.Rod("pvc"), [0.2], 1e5), ("rods",)),
        Row("ebantenna.fem.coupled_sweep.coupled_sweep", "contacts-nan",
            lambda: coupled_sweep.coupled_sweep(P, [fem.Rod("pvc")], [NAN], 1e5), ("contacts",)),
        Row("ebantenna.fem.plot.plot_modes", "result-int", lambda: plot.plot_modes(5),
            ("result",)),
        Row("ebantenna.fem.plot.plot_probe", "probe-int", lambda: plot.plot_probe(5),
            ("probe",)),
        Row("ebantenna.fem.plot.plot_probe", "supports-str", lambda: plot.plot_probe(P, "x"),
            ("supports",)),
        Row("ebantenna.fem.plot.plot_zones", "zones-int", lambda: plot.plot_zones(5),
            ("zones",)),
    ]


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.fem.')
