"""The sweeps solved on threads against the same sweeps solved one batch after another.

``map_on_cores`` takes one thread per core, ``os.cpu_count()``: set to 1 it runs the batches in
order on one thread, set to 4 it runs four at once, whatever the machine has.
"""

import os
import threading

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.fem import Rod
from ebantenna.fem._parallel import map_on_cores
from ebantenna.fem.coupled_sweep import coupled_sweep
from ebantenna.fem.sweeps import natural_frequencies

PROBE = Probe(tip_mass=0.002)
CONTACTS = np.linspace(0.01, 0.39, 23)


def on_cores(monkeypatch, n, run):
    """``run()`` with the machine taken to have ``n`` cores."""
    with monkeypatch.context() as patch:
        patch.setattr(os, "cpu_count", lambda: n)
        return run()


def test_the_threads_really_run_side_by_side_and_one_core_runs_in_order(monkeypatch):
    # passes only if two items run at the same time; run in turn, the first waits forever, and
    # the timeout ends that: 30 s is for the second thread to be started and scheduled, which a
    # scheduler does within milliseconds even at a load of tens of jobs per core (no CPU work)
    meet = threading.Barrier(2, timeout=30)

    def wait(i):
        meet.wait()
        return i

    assert on_cores(monkeypatch, 4, lambda: map_on_cores(wait, range(2))) == [0, 1]
    seen = []
    assert on_cores(monkeypatch, 1, lambda: map_on_cores(seen.append, range(5))) == [None] * 5
    assert seen == [0, 1, 2, 3, 4]


@pytest.mark.parametrize("method", ["banded", "dense", "secular"])
def test_a_threaded_sweep_equals_the_serial_one_bit_for_bit(monkeypatch, method):
    # Each batch is solved by the same code on the same numbers, with BLAS on one thread in both
    # runs; batches share no sums and come back in order: threads cannot change one bit.
    def sweep():
        return natural_frequencies(PROBE, CONTACTS, hinge=5.0, contact_stiffness=400.0,
                                   n_elements=24, n_modes=4, chunk=5, method=method)

    serial = on_cores(monkeypatch, 1, sweep)
    threaded = on_cores(monkeypatch, 4, sweep)
    assert serial.shape == (CONTACTS.size, 4)
    np.testing.assert_array_equal(threaded, serial)


def test_a_threaded_coupled_sweep_equals_the_serial_one_bit_for_bit(monkeypatch):
    # one position per item, as above: the same arithmetic, whichever thread runs it
    def sweep():
        return coupled_sweep(PROBE, [Rod("steel"), Rod("pvc")], CONTACTS[::4], 2e5, n_modes=3,
                             n_elements=16, rod_elements=8, probe_modes=12, rod_modes=6)

    serial = on_cores(monkeypatch, 1, sweep)
    threaded = on_cores(monkeypatch, 4, sweep)
    for name in ("frequencies", "damping_ratio", "tip_displacement"):
        np.testing.assert_array_equal(getattr(threaded, name), getattr(serial, name))


def test_blas_runs_on_one_thread_inside_on_either_path_and_its_count_comes_back(monkeypatch):
    # one item runs in the calling thread, several on a pool: both under the one-thread limit,
    # which is lifted afterwards (the controller that sets it is found once and reused)
    from threadpoolctl import threadpool_info, threadpool_limits

    def blas_threads(_):
        return {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}

    with threadpool_limits(limits=2, user_api="blas"):
        outside = blas_threads(None)
        for cores, items in ((1, range(1)), (4, range(1)), (4, range(3))):
            inside = on_cores(monkeypatch, cores,
                              lambda items=items: map_on_cores(blas_threads, items))
            assert inside == [{1}] * len(items)
            assert blas_threads(None) == outside
