"""The drivers' register access through the kernel: Linux's ``i2c-stub`` fake bus via smbus2.

``i2c-stub`` (``modprobe i2c-stub chip_addr=0x40,0x68``) gives plain 256-byte register files at the
chosen addresses behind a real ``/dev/i2c-N``: no sampling and no FIFO, but every ioctl goes
through the same kernel path as on the rig. Where no such bus is present the tests are skipped
and say how to get one.
"""

from pathlib import Path

import pytest

from ebantenna.chips.mpu6050 import WHO_AM_I_VALUE, Register
from ebantenna.chips.pca9685 import Register as PcaRegister
from ebantenna.device import MPU6050, PCA9685, I2CDevice, SystemClock

STUB_NAME = "SMBus stub driver"  # the adapter name i2c-stub registers


def _stub_bus() -> int | None:
    for adapter in sorted(Path("/sys/class/i2c-adapter").glob("i2c-*")):
        name = (adapter / "name").read_text().strip() if (adapter / "name").exists() else ""
        if name == STUB_NAME and Path(f"/dev/{adapter.name}").exists():
            return int(adapter.name.split("-")[1])
    return None


BUS = _stub_bus()
pytestmark = pytest.mark.skipif(
    BUS is None,
    reason="Linux's i2c-stub is not loaded: as root, 'modprobe i2c-dev; modprobe i2c-stub "
    "chip_addr=0x40,0x68' (needs the module in the running kernel and permission on /dev/i2c-N)",
)


@pytest.fixture
def bus():
    from smbus2 import SMBus

    with SMBus(BUS) as smbus:
        yield smbus


def test_register_reads_and_writes_go_through_the_kernel(bus):
    device = I2CDevice(bus, 0x68, clock=SystemClock())
    device.write_byte(Register.SMPLRT_DIV, 7)
    device.write_block(Register.ACCEL_XOUT_H, [1, 2, 3, 4, 5, 6])
    assert device.read_byte(Register.SMPLRT_DIV) == 7
    assert device.read_block(Register.ACCEL_XOUT_H, 6) == bytes([1, 2, 3, 4, 5, 6])


def test_mpu6050_identity_and_configuration_through_the_kernel(bus):
    bus.write_byte_data(0x68, Register.WHO_AM_I, WHO_AM_I_VALUE)  # a register file: set it
    mpu = MPU6050(bus, clock=SystemClock())
    mpu.check_identity()
    mpu.configure()
    assert mpu.configuration_lost() is None  # every setting reads back


def test_pca9685_set_up_through_the_kernel(bus):
    pca = PCA9685(bus, clock=SystemClock())
    pca.initialize()
    assert bus.read_byte_data(0x40, PcaRegister.PRE_SCALE) == pca.prescale
    pca.set_pulse(0, 1.5e-3)
    assert pca.pulse(0) == pytest.approx(1.5e-3, abs=1 / (4096 * pca.frequency))
