"""The engine of the contact laws' march: read each linear state a block of steps ahead.

:func:`.linear_state.march_step_by_step` takes every step in turn. Within one state the motion
is a sum of modes, so whether an event lies ahead, and the output samples, can be read for a
whole block of steps by one small matrix product (:meth:`.linear_state.LinearState.read_ahead`);
where a bound shows that no event can happen (a settled contact), a longer span is read at the
output samples only. Only the step that holds an event is taken through the law's
``advance``. The same events and, up to the rounding of the propagation, the same signals as
the reference; this is the default because it costs about one matrix product per block instead
of a propagation per step.
"""

from __future__ import annotations

__all__ = ["march_in_blocks"]


def march_in_blocks(system, x, key, n_steps: int):
    """March ``system`` (a :class:`.linear_state.SwitchedSystem`) ``n_steps`` steps from the
    state ``(x, key)`` at step 0, reading each state in blocks; returns ``(x, key)`` after the
    last step. Takes the checked values a contact law was built from."""
    h, sub = system.h, system.sub
    i = 0
    while i < n_steps:
        if system.interrupts(i):
            x, key = system.interrupted_step(x, key, i)
            i += 1
            system.record(i, x, key)
            continue
        st = system.state(key)
        limit = system.horizon(i, n_steps)
        first = (-(i + 1)) % sub  # the first step from here that is an output sample
        z = st.modal(x)
        quiet = system.quiet(key, x, z, min(st.span, limit))
        m, j, values, event = st.read_ahead(x, z, first, limit, quiet, system.ends(key))
        system.record_block(i, j, values, x, z, key)
        if m:
            x = st.after(x, z, m)
            i += m
            system.moved()
        if event:
            x, key = system.advance(x, key, i * h, (i + 1) * h, crosses=True)
            system.moved()
            i += 1
            system.record(i, x, key)
    return x, key
