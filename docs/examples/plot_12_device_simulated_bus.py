"""
The rig's driver on a simulated I2C bus
=======================================

The drivers in :mod:`ebantenna.device` talk to the MPU6050 accelerometer and the PCA9685 servo board
register by register, as on the Raspberry Pi. :class:`~ebantenna.device.simulated.rig.SimulatedRig`
answers those same register reads and writes, with a virtual clock and a simulated contact, so that
the search of the paper (sweep, detect the touch, stop the servos, record, release) runs without
hardware. Injected I2C faults show what the driver does with them: it retries harmless register
reads, but never a FIFO read blindly (a retry there would shift every later sample); it restarts the
FIFO instead and counts the samples of the gap as lost. The simulated chip keeps the ground truth,
so the example also counts the kept samples that differ from it: none.

The figure draws the recording without faults as a thick grey line and the one with faults as
thin red dots over it; where the dots are missing, samples were lost, as the legend counts. The two
are separate runs, not one recording with and without faults: the contact was detected at sample
418 in one and 428 in the other (the log below), and the samples differ. That the dots follow the
line shows only that the runs are alike; that each kept sample is right is what the printed count
``wrong=0`` says, each kept sample compared with the simulated chip's ground truth.
"""

import logging
import sys

import matplotlib.pyplot as plt

from ebantenna.device import (
    MPU6050,
    PCA9685,
    Faults,
    PanTilt,
    SearchConfig,
    SimulatedRig,
    search_and_record,
)

# %%
# The drivers log what they do through Python's ``logging`` (logger ``ebantenna.device``): each
# chip's set-up, the contact, and every retried I2C transfer, at level INFO. Here that log is
# printed with the example's output, one line per event, and kept there (``propagate = False``): the
# retries are what this example is about.
log = logging.getLogger("ebantenna.device")
handler = logging.StreamHandler(sys.stdout)
handler.setFormatter(logging.Formatter("    log: %(message)s"))
log.addHandler(handler)
log.setLevel(logging.INFO)
log.propagate = False

results = {}
for rate in (0.0, 0.02):
    rig = SimulatedRig.for_contact(scene="paper", material="wood", ratio=0.5, seed=4,
                                   faults=Faults(error_rate=rate))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    result = search_and_record(mpu, unit, SearchConfig(duration=0.5))
    rig.bus.close()
    results[rate] = result
    print(f"fault rate {rate:.0%}: contact={result.contact_detected}, "
          f"servos stopped={result.servos_stopped}, samples={result.samples}, "
          f"lost={result.samples_lost}, wrong={rig.wrong_samples(mpu, result.recording)}, "
          f"I2C retries={result.i2c_retries}, FIFO restarts={result.stream['fifo_restarts']}")
log.removeHandler(handler)  # the driver's log back to wherever the application sends it
log.propagate = True
log.setLevel(logging.NOTSET)

# %%
# With 2 % of the transfers failing, every failed transfer was retried and went through at the
# second attempt, and no kept sample differs from the simulated chip's ground truth. The retried
# reads of register 0x74 are FIFO reads (``FIFO_R_W``): retried only because the chip did not
# acknowledge (errno 121, "Remote I/O error"), which proves that it sent nothing. Any other
# failure of a FIFO read would have restarted the FIFO and counted the gap as lost; here none
# did, so no sample was lost.

fig, ax = plt.subplots(figsize=(7, 3.5))
styles = {0.0: {"color": "0.7", "lw": 3.0}, 0.02: {"color": "tab:red", "ls": "", "marker": ".",
                                                  "ms": 2.0}}
for rate, result in results.items():
    rec = result.recording
    ax.plot(rec.t - rec.t[0], rec.az, **styles[rate],
            label=f"Z, {rate:.0%} of transfers failing: {result.samples_lost} samples lost, "
                  f"{result.stream['fifo_restarts']} FIFO restarts")
ax.set_xlabel("time after the contact (s)")
ax.set_ylabel("acceleration (m/s$^2$)")
ax.legend(fontsize="small")
fig.tight_layout()
plt.show()
