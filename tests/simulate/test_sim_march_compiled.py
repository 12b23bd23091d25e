"""The compiled strike march (numba, the ``fast`` extra) against the NumPy block engine, and the
choice between them: the environment variable, the fallback and its one message.

Both marches run the same algorithm on the same tables; they differ in the order of the sums
that read a state (a loop against a BLAS product), so by a few ulps of the largest term of
each reading. On a strike whose events are well separated that is the bound the project holds
its two NumPy marches to (:mod:`test_sim_marches`): the same events, each within the root
finder's resolution, and signals within the rounding of the propagation carried by the
conditioning. Near the tip the strikes chatter, and there the NumPy march itself, started one
ulp away, leaves that bound (and can count other events): a property of the strike, tested
here, to which the compiled march is held as far as the physics allows.
"""

from __future__ import annotations

import copy
import logging
import sys

import numpy as np
import pytest

from ebantenna import _engines as _engine_choice
from ebantenna.simulate import _block_march, builtin_scene, simulate_batch, unilateral
from ebantenna.simulate.unilateral import ChatterError, HertzStrikeLaw

EPS = np.finfo(float).eps
STATUS = _block_march.compiled_status()
needs_numba = pytest.mark.skipif(
    not STATUS.available, reason=f"the compiled strike march is not available: {STATUS.reason}")


def _capture(scene, contacts, materials):
    """The strike laws of ``scene`` at ``contacts`` x ``materials`` as the simulator builds
    them, each ``(law, x, key, n_steps)`` copied before its march."""
    got = []
    march = unilateral.MARCHES["blocks"]

    def spy(law, x, key, n_steps):
        got.append(copy.deepcopy((law, x, key, n_steps)))
        return march(law, x, key, n_steps)

    c = np.repeat(contacts, len(materials))
    m = np.array(list(materials) * len(contacts), dtype=object)
    unilateral.MARCHES["blocks"] = spy
    try:
        simulate_batch(scene, contact=c, material=m, sweep_speed=np.full(c.size, 0.5),
                       tilt_ratio=np.full(c.size, 0.25), seeds=np.arange(c.size),
                       show_progress=False, x_modes=False)  # fmt: skip
    finally:
        unilateral.MARCHES["blocks"] = march
    return got


def _march(strike, engine, ulps=0):
    """March a copy of ``strike`` with ``engine`` ('compiled': the compiled march alone; 'numpy'
    or 'auto': :func:`march_in_blocks`'s choice), its initial state
    moved by ``ulps`` units in the last place of its largest entry; the law afterwards."""
    law, x, key, n_steps = copy.deepcopy(strike)
    if isinstance(law, HertzStrikeLaw):  # its chords are found by identity: renew after a copy
        law.index = {id(st): j for j, st in enumerate(law.segments)}
    if ulps:
        k = int(np.argmax(np.abs(x)))  # at the first touch: the servo's speed
        x = x.copy()
        for _ in range(abs(ulps)):
            x[k] = np.nextafter(x[k], np.inf if ulps > 0 else -np.inf)
    if engine == "compiled":
        assert _block_march.march_compiled(law, x, key, n_steps) is not None
    else:
        _block_march.march_in_blocks(law, x, key, n_steps, engine=engine)
    return law


def _bound(law):
    """The two-march bound of :mod:`test_sim_marches`, per unit of the signal's peak: an
    event moved by ``2 time_tolerance`` moves the motion by the fastest rate ``|lambda|`` times
    that, and each step rounds the state by eps times its eigenvectors' condition."""
    states = [law.free, *law.segments] if isinstance(law, HertzStrikeLaw) else [law.free,
                                                                                  law.closed]
    n_steps = (law.acc.size - 1) * law.sub
    lam = max(np.abs(st.lam).max() for st in states)
    cond = max(np.linalg.cond(st.V) for st in states)
    return lam * 2 * law.xtol + n_steps * EPS * cond


def _assert_same(a, b):
    """``b`` has ``a``'s events, each within the root finder's resolution, and its signals
    within :func:`_bound`."""
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    # each event lies within time_tolerance after its root in both marches
    np.testing.assert_allclose([e.time for e in b.events], [e.time for e in a.events], rtol=0,
                               atol=2 * a.xtol)  # fmt: skip
    np.testing.assert_allclose([e.velocity for e in b.events], [e.velocity for e in a.events],
                               rtol=0, atol=_bound(a) * max(abs(e.velocity) for e in a.events))
    assert b.stopped == a.stopped
    for name in ("acc", "force"):
        x, y = getattr(b, name), getattr(a, name)
        np.testing.assert_allclose(x, y, rtol=0, atol=_bound(a) * np.abs(y).max())


@pytest.fixture(scope="module")
def paper_strikes():
    """The paper scene's strikes (0.4 s) on the five materials at four contacts away from the
    tip's chatter."""
    scene = builtin_scene("paper").with_(duration=0.4)
    return _capture(scene, [0.05, 0.15, 0.25, 0.35], ["aluminium", "brass", "pvc", "steel",
                                                     "wood"])


@pytest.fixture(scope="module")
def hertz_strikes():
    """The same scene's strikes through the Hertz law's chords."""
    paper = builtin_scene("paper").with_(duration=0.4)
    scene = paper.with_(name="paper-hertz", effects=(*paper.effects, "hertz_contact"))
    return _capture(scene, [0.1, 0.3], ["brass", "steel"])


@needs_numba
def test_the_compiled_march_reproduces_the_engine_on_paper_strikes(paper_strikes):
    assert len(paper_strikes) == 20
    for strike in paper_strikes:
        numpy = _march(strike, "numpy")
        assert len(numpy.events) >= 2  # it leaves and strikes again
        _assert_same(numpy, _march(strike, "compiled"))


@needs_numba
def test_the_compiled_march_reproduces_the_engine_on_hertz_strikes(hertz_strikes):
    assert all(isinstance(s[0], HertzStrikeLaw) for s in hertz_strikes)
    for strike in hertz_strikes:
        numpy, compiled = _march(strike, "numpy"), _march(strike, "compiled")
        assert numpy.chord_changes > 0 and compiled.chord_changes == numpy.chord_changes
        _assert_same(numpy, compiled)


@pytest.fixture(scope="module")
def chattering_strikes():
    """Paper strikes (1 s) near the tip, where the probe chatters on the object."""
    scene = builtin_scene("paper").with_(duration=1.0)
    return _capture(scene, [0.389, 0.393, 0.396], ["aluminium", "steel"])


def _event_shift(a, b):
    """The largest shift of an event between two marches with the same events."""
    return max(abs(e.time - f.time) for e, f in zip(a.events, b.events, strict=True))


@needs_numba
def test_near_the_tip_the_events_are_a_property_of_the_last_bits(chattering_strikes):
    # The NumPy march against itself started one ulp away (the servo's speed): what the strike
    # makes of a change of the last bit. The two marches' readings differ by the order of
    # their sums, at most 2n ulps of the largest term for 2n modes (Higham, *Accuracy and
    # Stability of Numerical Algorithms*, 2nd ed., SIAM 2002, eq. 4.4): where both keep the
    # events (the difference grows smoothly), the compiled march lies within 2n times what one
    # ulp makes, besides the root finder's resolution. One ulp of the start probes one direction
    # only, while the compiled march rounds differently at every step; a chattering strike
    # multiplies a timing difference at each re-strike, so the compiled march may strike again a
    # different number of times where that probe did not (measured on a CPU with AVX2 and no
    # AVX-512, steel at 0.396 m: the two marches' event times 9e-17 s apart at the 4th event,
    # 3e-11 at the 24th, 1e-7 at the 56th, and the NumPy march against itself one ulp away
    # alike; 234 events against 252 and 222). Then the two start as one march, their first
    # event within the root finder's resolution, and part later.
    sensitive = count_moved = checked = 0
    for strike in chattering_strikes:
        numpy = _march(strike, "numpy")
        spread = [_march(strike, "numpy", ulps) for ulps in (1, -1)]
        compiled = _march(strike, "compiled")
        kinds = [e.kind for e in numpy.events]
        if all([e.kind for e in p.events] == kinds for p in (*spread, compiled)):
            modes, peak = 2 * numpy.free.n, np.abs(numpy.acc).max()
            shift = max(_event_shift(numpy, p) for p in spread)
            sensitive += shift > 1000 * 2 * numpy.xtol  # far beyond the root finder's
            assert _event_shift(numpy, compiled) <= 2 * numpy.xtol + modes * shift
            ulp_diff = max(np.abs(p.acc - numpy.acc).max() for p in spread)
            assert np.abs(compiled.acc - numpy.acc).max() <= (
                _bound(numpy) * peak + modes * ulp_diff)
            checked += 1
        else:  # the last bits decide how often the probe strikes again
            count_moved += 1
            first = numpy.events[0]
            for other in (*spread, compiled):
                assert other.events[0].kind == first.kind
                assert abs(other.events[0].time - first.time) <= 2 * numpy.xtol
    # near the tip the re-strikes are decided by the last bits: their times (and, for some
    # strikes, their number) are no property of one march; where they are kept, the compiled
    # march is held to the bound
    assert sensitive >= 2 and count_moved >= 1 and checked >= 2


@needs_numba
def test_a_strike_past_max_events_is_left_to_the_engine(paper_strikes):
    strike = copy.deepcopy(paper_strikes[0])
    strike[0].max_events, strike[0].on_max_events = 3, "raise"
    with pytest.raises(ChatterError):
        _block_march.march_in_blocks(*strike, engine="compiled")
    strike = copy.deepcopy(paper_strikes[0])
    strike[0].max_events = 3
    assert _block_march.march_compiled(*strike) is None  # gave up: no event kept
    assert strike[0].events == []


@pytest.fixture
def fresh_status():
    """Probe numba again in this test, and once more after it."""
    _block_march.compiled_status.cache_clear()
    yield
    _block_march.compiled_status.cache_clear()


def test_without_numba_the_engine_marches_and_says_why_once(monkeypatch, fresh_status, caplog,
                                                            paper_strikes):  # fmt: skip
    monkeypatch.setattr(_engine_choice.importlib.util, "find_spec",
                        lambda name, *args: None if name == "numba" else sys.modules[name])
    monkeypatch.delenv(_engine_choice.ENGINE_VARIABLE, raising=False)
    called = []
    monkeypatch.setattr(_block_march, "march_compiled", lambda *a: called.append(a))
    with caplog.at_level(logging.INFO, logger=_engine_choice.__name__):
        laws = [_march(paper_strikes[k], "auto") for k in (0, 1)]
    assert not called and all(len(law.events) >= 2 for law in laws)
    messages = [r.getMessage() for r in caplog.records if r.name == _engine_choice.__name__]
    assert len(messages) == 1 and "numba is not installed" in messages[0]
    assert "strike" in messages[0] and "ebantenna[fast]" in messages[0]
    with pytest.raises(RuntimeError, match="compiled strike march was asked for but numba"):
        _block_march.march_in_blocks(*copy.deepcopy(paper_strikes[0]), engine="compiled")


def test_the_engine_variable_chooses(monkeypatch, paper_strikes):
    _block_march.compiled_status()  # loaded (and checked) before the march is replaced
    called = []
    monkeypatch.setattr(_block_march, "march_compiled", lambda *a: called.append(a))
    monkeypatch.setenv(_engine_choice.ENGINE_VARIABLE, "numpy")
    _block_march.march_in_blocks(*copy.deepcopy(paper_strikes[0]))
    assert not called
    monkeypatch.setenv(_engine_choice.ENGINE_VARIABLE, "auto")
    _block_march.march_in_blocks(*copy.deepcopy(paper_strikes[0]))
    assert len(called) == (1 if STATUS.available else 0)
    monkeypatch.setenv(_engine_choice.ENGINE_VARIABLE, "fortran")
    with pytest.raises(ValueError, match="EBANTENNA_ENGINE must be one of"):
        _block_march.march_in_blocks(*copy.deepcopy(paper_strikes[0]))


def test_what_the_compiled_march_takes(paper_strikes):
    law = copy.deepcopy(paper_strikes[0])[0]
    assert _block_march.compiled_fits(law)
    law.trajectory = np.zeros((law.acc.size, 2 * law.base.size + 2))
    assert not _block_march.compiled_fits(law)  # the states recorded: the NumPy engine


@pytest.mark.parametrize("interrupt", [KeyboardInterrupt(), SystemExit(143)])
def test_an_interrupt_inside_compiled_code_reaches_the_caller_as_itself(interrupt):
    """numba turns a signal handler's exception raised inside its C code into a SystemError
    caused by it; the engines re-raise the interrupt, so that the caller's clean-up runs."""
    def compiled_call():
        try:
            raise interrupt
        except BaseException as exc:
            raise SystemError("<function _numba_unpickle> returned a result with an "
                              "exception set") from exc

    with pytest.raises(type(interrupt)), _engine_choice.interrupts_pass_through():
        compiled_call()
    with pytest.raises(SystemError), _engine_choice.interrupts_pass_through():
        raise SystemError("a SystemError of its own")
