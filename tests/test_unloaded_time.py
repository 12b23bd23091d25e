"""The tests' load-proof clock (``unloaded_time``): waits for a CPU left out, computing and
blocking counted."""

import os
import subprocess
import sys
import time

import pytest
from unloaded_time import UnloadedClock, communicate, run, time_limit

HAS_SCHEDSTAT = os.path.exists("/proc/thread-self/schedstat")


@pytest.mark.skipif(not HAS_SCHEDSTAT, reason="the kernel gives no run-queue time here")
def test_a_computation_sharing_its_core_counts_its_cpu_time_not_its_wall_time():
    # pinned to one core beside a process that spins there: the loop gets a share of the core,
    # and the clock must read the loop's CPU time (it never sleeps), not the wall time
    core = min(os.sched_getaffinity(0))
    spin = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    before = os.sched_getaffinity(0)
    try:
        os.sched_setaffinity(spin.pid, {core})
        os.sched_setaffinity(0, {core})
        clock, cpu = UnloadedClock(), time.thread_time()
        end = cpu + 0.3
        while time.thread_time() < end:
            pass
        elapsed, cpu = clock.elapsed(), time.thread_time() - cpu
    finally:
        os.sched_setaffinity(0, before)
        spin.kill()
        spin.wait()
    # the two clocks read the same scheduler accounting; they differ by the reads themselves
    # and the scheduler's tick (a few ms)
    assert cpu - 0.02 <= elapsed <= cpu + 0.05, (elapsed, cpu)


def test_blocking_counts_and_a_limit_interrupts_a_blocked_call(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    clock = UnloadedClock()
    with pytest.raises(TimeoutError), time_limit(0.2, TimeoutError):
        open(fifo, "rb")  # no writer: blocks until the limit interrupts it
    assert clock.elapsed() >= 0.2


def test_a_call_within_its_limit_returns_and_the_alarm_is_cleared():
    with time_limit(30, TimeoutError) as clock:
        total = sum(range(1000))
    assert total == 499500 and 0 <= clock.elapsed() < 30
    time.sleep(0.05)  # no alarm left behind


def test_a_child_past_its_limit_is_killed_with_what_it_printed():
    proc = subprocess.Popen([sys.executable, "-c", "import time; print('up', flush=True); "
                             "time.sleep(600)"], stdout=subprocess.PIPE, text=True)
    with pytest.raises(subprocess.TimeoutExpired) as caught:
        communicate(proc, 0.5)
    assert proc.returncode is not None and caught.value.output == "up\n"


def test_run_returns_what_the_child_printed_and_its_code():
    done = run([sys.executable, "-c", "import sys; print('out'); sys.exit(3)"], 60,
               capture_output=True, text=True)
    assert (done.returncode, done.stdout) == (3, "out\n")
