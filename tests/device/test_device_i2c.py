"""Retries, back-off and block reads of I2CDevice, against a scripted bus."""

import errno

import pytest

from ebantenna.device import I2CDevice, I2CError, RetryPolicy, SimulatedRig, VirtualClock


class ScriptedBus:
    """Fails the first ``failures`` transfers with ``err``, then answers with register numbers."""

    def __init__(self, failures=0, err=errno.EREMOTEIO):
        self.failures = failures
        self.err = err
        self.calls = []

    def _maybe_fail(self):
        if self.failures:
            self.failures -= 1
            raise OSError(self.err, "scripted failure")

    def read_byte_data(self, addr, reg, force=None):
        self.calls.append(("rb", addr, reg))
        self._maybe_fail()
        return reg

    def write_byte_data(self, addr, reg, value, force=None):
        self.calls.append(("wb", addr, reg, value))
        self._maybe_fail()

    def read_i2c_block_data(self, addr, reg, length, force=None):
        self.calls.append(("rblk", addr, reg, length))
        self._maybe_fail()
        return [(reg + k) & 0xFF for k in range(length)]

    def write_i2c_block_data(self, addr, reg, data, force=None):
        self.calls.append(("wblk", addr, reg, tuple(data)))
        self._maybe_fail()


class RecordingClock(VirtualClock):
    def __init__(self):
        super().__init__()
        self.sleeps = []

    def sleep(self, seconds):
        self.sleeps.append(seconds)
        super().sleep(seconds)


def test_retry_policy_delays_grow_geometrically_and_are_capped():
    policy = RetryPolicy(attempts=6, initial_delay=0.001, factor=2.0, max_delay=0.005)
    assert policy.delays() == (0.001, 0.002, 0.004, 0.005, 0.005)
    assert RetryPolicy(attempts=1).delays() == ()


@pytest.mark.parametrize(
    "kwargs, match",
    [({"attempts": 0}, "attempts"), ({"factor": 0.5}, "factor"), ({"initial_delay": -1}, "initial"),
     ({"max_delay": float("nan")}, "max_delay")],
)
def test_retry_policy_rejects_bad_values(kwargs, match):
    with pytest.raises(ValueError, match=match):
        RetryPolicy(**kwargs)


def test_transient_errors_are_retried_with_the_policy_delays():
    bus, clock = ScriptedBus(failures=3), RecordingClock()
    policy = RetryPolicy(attempts=5, initial_delay=0.001, factor=3.0, max_delay=1.0)
    dev = I2CDevice(bus, 0x68, retry=policy, clock=clock)
    assert dev.read_byte(0x75) == 0x75
    assert dev.retries == 3
    assert clock.sleeps == pytest.approx([0.001, 0.003, 0.009])
    assert len(bus.calls) == 4


def test_exhausted_retries_raise_a_clear_error():
    bus, clock = ScriptedBus(failures=100), RecordingClock()
    dev = I2CDevice(bus, 0x40, retry=RetryPolicy(attempts=4), clock=clock)
    with pytest.raises(I2CError, match=r"register 0xFD at address 0x40 failed after 4 attempts"
                       r".*check the wiring") as info:
        dev.write_byte(0xFD, 0x10)
    assert info.value.errno == errno.EREMOTEIO
    assert isinstance(info.value, OSError)
    assert len(bus.calls) == 4 and len(clock.sleeps) == 3
    # Bounded: the total wait never exceeds (attempts - 1) * max_delay.
    assert sum(clock.sleeps) <= 3 * RetryPolicy().max_delay


def test_non_transient_errors_are_not_retried():
    bus = ScriptedBus(failures=5, err=errno.EACCES)
    dev = I2CDevice(bus, 0x68, clock=RecordingClock())
    with pytest.raises(PermissionError):
        dev.read_byte(0x00)
    assert len(bus.calls) == 1 and dev.retries == 0


def test_long_reads_are_split_into_smbus_blocks():
    bus = ScriptedBus()
    dev = I2CDevice(bus, 0x68, clock=RecordingClock())
    data = dev.read_block(0x10, 70)
    assert [c[2:] for c in bus.calls] == [(0x10, 32), (0x30, 32), (0x50, 6)]
    assert list(data) == list(range(0x10, 0x10 + 70))
    bus.calls.clear()
    dev.read_block(0x74, 65, increment=False, chunk=30)
    assert [c[2:] for c in bus.calls] == [(0x74, 30), (0x74, 30), (0x74, 5)]


@pytest.mark.parametrize(
    "call, match",
    [(lambda d: d.read_byte(256), "register"), (lambda d: d.write_byte(1, -1), "value"),
     (lambda d: d.write_block(1, []), "data"), (lambda d: d.write_block(1, [0] * 33), "data"),
     (lambda d: d.read_block(0xF0, 32), "past 0xFF"), (lambda d: d.read_block(0, 4, chunk=33),
                                                       "chunk")],
)
def test_bad_arguments_name_the_parameter(call, match):
    dev = I2CDevice(ScriptedBus(), 0x68, clock=RecordingClock())
    with pytest.raises(ValueError, match=match):
        call(dev)


def test_address_is_checked():
    with pytest.raises(ValueError, match="address"):
        I2CDevice(ScriptedBus(), 0x80)
    with pytest.raises(TypeError, match="retry"):
        I2CDevice(ScriptedBus(), 0x68, retry=3)


def test_combined_transfer_reads_more_than_32_bytes_at_once():
    rig = SimulatedRig.quiet()
    dev = I2CDevice(rig.bus, 0x68, clock=rig.clock, use_rdwr=True)
    before = rig.bus.transfers
    rig.mpu.regs[0x41:0x72] = bytes(range(0x41, 0x72))  # mark each register with its address
    data = dev.read_block(0x40, 52)  # 0x40-0x73: past the 32-byte SMBus limit, in one transfer
    assert rig.bus.transfers == before + 1
    # ACCEL_ZOUT_L of a sleeping chip, registers 0x41-0x71, then FIFO_COUNT = 0.
    assert data == bytes([0]) + bytes(range(0x41, 0x72)) + bytes(2)


def test_missing_chip_is_reported_after_retries():
    rig = SimulatedRig.quiet()
    dev = I2CDevice(rig.bus, 0x50, clock=rig.clock)
    with pytest.raises(I2CError, match="0x50"):
        dev.read_byte(0)


@pytest.mark.parametrize("err", [errno.EIO, errno.ETIMEDOUT, errno.EAGAIN])
def test_a_read_with_a_side_effect_is_not_retried_after_an_error_that_may_be_late(err):
    bus = ScriptedBus(failures=1, err=err)
    dev = I2CDevice(bus, 0x68, clock=RecordingClock())
    with pytest.raises(I2CError, match="failed after 1 attempt"):
        dev.read_block(0x74, 30, increment=False, chunk=30, retry=False)
    assert len(bus.calls) == 1 and dev.retries == 0
    with pytest.raises(I2CError):
        I2CDevice(ScriptedBus(failures=1, err=err), 0x68, clock=RecordingClock()).read_byte(
            0x3A, retry=False)


def test_a_missing_acknowledge_proves_nothing_was_read_and_is_retried():
    bus = ScriptedBus(failures=2, err=errno.EREMOTEIO)
    dev = I2CDevice(bus, 0x68, clock=RecordingClock())
    data = dev.read_block(0x74, 6, increment=False, retry=False)
    assert data == bytes([0x74 + k for k in range(6)])
    assert dev.retries == 2 and len(bus.calls) == 3
    # a write made once is never retried, not even after a missing acknowledge
    with pytest.raises(I2CError):
        I2CDevice(ScriptedBus(failures=1), 0x68, clock=RecordingClock()).write_byte(
            0x6A, 0x40, retry=False)


def test_a_short_read_is_an_error():
    class ShortBus(ScriptedBus):
        def read_i2c_block_data(self, addr, reg, length, force=None):
            return super().read_i2c_block_data(addr, reg, length)[: length - 1]

    dev = I2CDevice(ShortBus(), 0x68, clock=RecordingClock())
    with pytest.raises(I2CError, match="short read: 5 of 6 bytes"):
        dev.read_block(0x74, 6, increment=False, retry=False)
    with pytest.raises(I2CError, match="after 5 attempts"):  # retried like any transient error
        dev.read_block(0x3B, 6)
