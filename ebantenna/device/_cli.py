"""``ebantenna acquire``: search for an object, stop on contact and record the vibration."""

from __future__ import annotations

import argparse
import os
import sys

from .i2c import RASPBERRY_PI_BUS_HZ

#: What to do when /dev/i2c-N is missing (Raspberry Pi OS).
ENABLE_I2C_HINT = (
    "enable I2C on a Raspberry Pi with 'sudo raspi-config' (Interface Options > I2C) or the line "
    "'dtparam=i2c_arm=on' in /boot/firmware/config.txt, then reboot; 'sudo modprobe i2c-dev' "
    "loads the device files, and 'ls /dev/i2c-*' lists the buses ('i2cdetect -y 1' shows the "
    "chips: 0x40 PCA9685, 0x68 MPU-6050)")



def device_number(text: str) -> int:
    """The type of ``--bus`` and ``--oe-gpio``: a number >= 0, as Linux numbers its devices."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 0, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 0, got {text}")
    return value


def register(subparsers) -> None:
    """Add the ``acquire`` subcommand."""
    from ..cli import seed_argument
    from .pantilt import MAX_DURATION

    parser = subparsers.add_parser(
        "acquire",
        help="sweep the probe until it touches something, then record the vibration",
        description="Run the pan-tilt search of the paper (Figs. 7-8): sweep an elliptical path, "
        "stop the servos when the accelerometer reports a contact, record the vibration window "
        "and release the servos. --simulated runs on a simulated I2C bus (the scene simulator "
        "provides the vibration); --bus N drives the real rig on /dev/i2c-N. Exit code 0 on "
        "contact, 1 without one, 3 when the servos could not be released (the recording is "
        "saved all the same, to --out or acquire-unreleased.npz; cut the servo supply).",
    )
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--simulated", action="store_true", help="use the simulated rig")
    where.add_argument("--bus", type=device_number, metavar="N", help="I2C bus of the real rig")
    parser.add_argument("--material", default="brass",
                        help="touched material (simulated: what is simulated; hardware: a label)")
    parser.add_argument("--ratio", type=float, default=0.5,
                        help="contact distance over probe length, in (0, 1) (default 0.5)")
    parser.add_argument("--scene", default="paper", help="built-in scene for --simulated")
    parser.add_argument("--seed", type=seed_argument, default=0,
                        help="seed of the simulation, 0 ... 2**63 - 1 (0)")
    parser.add_argument("--inject-faults", type=float, default=0.0, metavar="RATE",
                        help="simulated only: fraction of I2C transfers that fail, every kind "
                        "(no acknowledge, EIO, ETIMEDOUT, EAGAIN, late errors, short reads)")
    parser.add_argument("--chip-reset-at", type=float, metavar="S",
                        help="simulated only: the accelerometer browns out at this time, s")
    parser.add_argument("--stuck-bus", type=float, nargs=2, metavar=("AT", "FOR"),
                        help="simulated only: the bus is stuck from AT for FOR seconds")
    parser.add_argument("--clock-drift", type=float, default=0.0, metavar="X",
                        help="simulated only: the accelerometer's clock runs (1 + X) fast")
    parser.add_argument("--free-running-divider", action="store_true",
                        help="simulated only: the sample-rate divider does not restart when the "
                        "FIFO is enabled")
    parser.add_argument("--repeat-last-byte", action="store_true",
                        help="simulated only: reading the FIFO past its end repeats the last byte")
    parser.add_argument("--transfer-timeout", type=float, default=0.0, metavar="S",
                        help="simulated only: a transfer that times out hangs S seconds first")
    parser.add_argument("--release-fails", action="store_true",
                        help="simulated only: every write that switches the servos off fails")
    parser.add_argument("--bus-hz", type=float, default=RASPBERRY_PI_BUS_HZ, metavar="HZ",
                        help="simulated only: I2C clock (default 100000, a Raspberry Pi's)")
    parser.add_argument("--oe-gpio", type=device_number, metavar="PIN",
                        help="BCM GPIO wired to the PCA9685's OE pin: releases the servos when "
                        "I2C cannot (needs the gpio extra; simulated: the rig's OE line)")
    parser.add_argument("--oscillator-hz", type=float, metavar="HZ",
                        help="PCA9685 oscillator frequency as calibrated (default 25 MHz)")
    parser.add_argument("--measured-pwm-hz", type=float, metavar="HZ",
                        help="PWM frequency measured on a PCA9685 output at the default 50 Hz "
                        "setting; calibrates the oscillator from it")
    parser.add_argument("--threshold", type=float, default=2.0,
                        help="contact threshold on the acceleration change, m/s^2 (default 2)")
    parser.add_argument("--duration", type=float, default=1.0,
                        help=f"recorded time after the contact, s, in (0, {MAX_DURATION:g}] "
                        "(default 1)")
    parser.add_argument("--out", metavar="FILE.npz", help="save the recording here")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=run)


#: Exit code of ``acquire`` when the servos could not be released (the recording is saved).
EXIT_NOT_RELEASED = 3

#: What to do when the servos could not be released.
CUT_SUPPLY = ("the servos could not be released and may still be powered: switch off the servo "
              "supply (V+ of the PCA9685) now")


def run(args: argparse.Namespace) -> int:
    """Run the acquisition; returns the exit code (0 on contact, 1 without one, 3 when the servos
    could not be released: the recording is then saved all the same)."""
    from .._validate import check_in_range
    from .pantilt import MAX_DURATION

    ratio = check_in_range("--ratio", args.ratio, 0.0, 1.0)
    check_in_range("--duration", args.duration, 0.0, MAX_DURATION, high_inclusive=True)
    setup = _setup(args, ratio)
    result, unreleased = _acquire(args, setup)
    summary = _summary(args, setup, result)
    if args.json:
        from ..cli import print_json

        print_json(summary)
    else:
        _print_text(summary, result, setup["config"])
    if unreleased:
        print(f"ebantenna acquire: {CUT_SUPPLY}", file=sys.stderr)
        return EXIT_NOT_RELEASED
    return 0 if result.contact_detected else 1


def _setup(args, ratio: float) -> dict:
    """The bus, clock, OE line, search settings and labels the arguments ask for."""
    from .._validate import output_path
    from ..probe import material as lookup_material
    from .pantilt import SearchConfig

    out = None if args.out is None else output_path("--out", args.out, ".npz")
    material = lookup_material(args.material).name
    setup = {"out": out, "oscillator": _oscillator(args), "rig": None, "oe": None,
             "config": SearchConfig(threshold=args.threshold, duration=args.duration),
             "labels": {"material": material, "ratio": ratio}}
    where = _simulated(args, material, ratio) if args.simulated else _hardware(args)
    setup["labels"].update(where.pop("labels"))
    setup.update(where)
    return setup


def _simulated(args, material: str, ratio: float) -> dict:
    """The simulated rig, with the faults asked for."""
    from .oe import OutputEnable
    from .simulated import Faults, SimulatedRig

    stuck_at, stuck_for = args.stuck_bus or (None, 0.0)
    faults = Faults.every_kind(
        args.inject_faults, chip_reset_at=args.chip_reset_at, stuck_at=stuck_at,
        stuck_duration=stuck_for, clock_drift=args.clock_drift,
        free_running_divider=args.free_running_divider, repeat_last_byte=args.repeat_last_byte,
        transfer_timeout=args.transfer_timeout, release_fails=args.release_fails)
    rig = SimulatedRig.for_contact(scene=args.scene, material=material, ratio=ratio,
                                   seed=args.seed, faults=faults)
    rig.bus.bus_hz = args.bus_hz
    oe = None if args.oe_gpio is None else OutputEnable(rig.oe_line())
    labels = {"scene": args.scene, "seed": args.seed, "simulated": True}
    return {"bus": rig.bus, "clock": rig.clock, "rig": rig, "oe": oe,
            "labels": labels}


def _hardware(args) -> dict:
    """The real rig on /dev/i2c-N (and its OE line, if wired)."""
    simulated_only = {"--inject-faults": args.inject_faults, "--chip-reset-at": args.chip_reset_at,
                      "--stuck-bus": args.stuck_bus, "--clock-drift": args.clock_drift,
                      "--free-running-divider": args.free_running_divider,
                      "--repeat-last-byte": args.repeat_last_byte,
                      "--transfer-timeout": args.transfer_timeout,
                      "--release-fails": args.release_fails,
                      "--bus-hz": args.bus_hz != RASPBERRY_PI_BUS_HZ}
    given = [name for name, value in simulated_only.items() if value]
    if given:
        raise ValueError(f"{', '.join(given)} work(s) only with --simulated")
    if not os.path.exists(f"/dev/i2c-{args.bus}"):
        raise FileNotFoundError(f"--bus {args.bus}: /dev/i2c-{args.bus} does not exist: no I2C "
                                f"bus {args.bus} on this machine. To {ENABLE_I2C_HINT}")
    from smbus2 import SMBus

    from .clock import SystemClock
    from .oe import OutputEnable

    oe = None if args.oe_gpio is None else OutputEnable.gpio(args.oe_gpio)
    return {"bus": SMBus(args.bus), "clock": SystemClock(), "oe": oe,
            "labels": {"bus": args.bus, "simulated": False}}


def _acquire(args, setup: dict):
    """Search and record; returns the result and whether the servos stayed unreleased.

    A recording that was made survives any failure after it: a stall saves the partial one and
    raises :class:`OSError`; a failed release keeps the finished one (saved by the caller).
    """
    from ..cli import Terminated, interrupted
    from .mpu6050 import MPU6050
    from .pantilt import PanTilt, search_and_record
    from .pca9685 import PCA9685
    from .safety import ReleaseError, SignalReceived
    from .watchdog import StreamStalledError

    bus, clock = setup["bus"], setup["clock"]
    try:
        # The servos first: switched off before anything else can fail (a missing
        # accelerometer must not leave them where an earlier run put them).
        unit = PanTilt(PCA9685(bus, clock=clock, oscillator_hz=setup["oscillator"]))
        unit.initialize()
        setup["mpu"] = mpu = MPU6050(bus, clock=clock)
        mpu.initialize()
        return search_and_record(mpu, unit, setup["config"], labels=setup["labels"],
                                 output_enable=setup["oe"]), False
    except ReleaseError as exc:
        if exc.result is None:
            raise
        return exc.result, True
    except StreamStalledError as exc:
        raise _stalled(exc, setup["out"]) from None
    except (KeyboardInterrupt, SignalReceived) as exc:
        partial = _interrupted_partial(args, setup, exc)
        if isinstance(exc, SignalReceived):  # SIGTERM or SIGHUP, as the servo guard saw it
            exc = Terminated(exc.signum)
        raise interrupted(exc, partial) from None
    finally:
        bus.close()
        if setup["oe"] is not None:
            setup["oe"].close()


def _stalled(exc, out) -> OSError:
    """The error a stalled stream ends ``acquire`` with, once its partial recording is saved."""
    saved = exc.recording.save(out or "acquire-partial.npz") if exc.recording is not None else None
    released = getattr(exc, "servos_released", False)
    return OSError(f"{exc}; servos {'released' if released else 'NOT confirmed released'}; "
                   + (f"partial recording saved to {saved}" if saved else "nothing to save"))


def _interrupted_partial(args, setup: dict, exc) -> dict:
    """What an interrupted run kept: search_and_record has released the servos on its way out;
    no recording is complete, but what the window held after a contact is saved, marked."""
    recording = getattr(exc, "recording", None)
    saved = None if recording is None else recording.save(setup["out"] or "acquire-partial.npz")
    return {"mode": "simulated" if args.simulated else "hardware", **setup["labels"],
            "contact_detected": True if recording is not None else None,
            "samples": None if recording is None else recording.n_samples,
            "out": None if saved is None else str(saved),
            "servos_released": getattr(exc, "servos_released", None)}


def _summary(args, setup: dict, result) -> dict:
    """The JSON summary (the command's contract), with the recording saved if asked (always
    when the servos could not be released: nothing made is dropped)."""
    summary = {"mode": "simulated" if args.simulated else "hardware", **setup["labels"],
               **result.summary(), "out": None, "pca9685_oscillator_hz": setup["oscillator"]}
    rig = setup["rig"]
    if rig is not None:
        summary["i2c_errors_injected"] = rig.bus.errors_injected
        summary["faults_injected"] = sorted({kind for _, kind in rig.bus.injector.log})
        summary["samples_wrong"] = (rig.wrong_samples(setup["mpu"], result.recording)
                                    if result.recording is not None else 0)
        summary["virtual_time_s"] = rig.clock.monotonic()
    out = setup["out"]
    if out is None and result.recording is not None and not result.servos_released:
        out = "acquire-unreleased.npz"
    if out is not None and result.recording is not None:
        summary["out"] = str(result.recording.save(out))
    if not result.servos_released:
        summary["action_required"] = CUT_SUPPLY
    return summary


def _print_text(summary: dict, result, config) -> None:
    """The human-readable report."""
    if result.contact_detected:
        print(f"contact after {result.contact_time:.3f} s at pan/tilt "
              f"{result.contact_angles[0]:.1f}/{result.contact_angles[1]:.1f} deg; "
              f"servos {'stopped' if result.servos_stopped else 'NOT confirmed stopped'}")
        print(f"recorded {result.samples} samples at {result.recording.fs:.2f} Hz "
              f"(estimated), {result.samples_lost} lost, {result.i2c_retries} I2C retries, "
              f"{summary['fifo_restarts']} FIFO restarts, {summary['fifo_counts_rejected']} "
              f"FIFO counts rejected; timestamps within "
              f"{1e6 * summary['timestamp_uncertainty_s']:.0f} us")
        if summary["out"]:
            print(f"saved {summary['out']}")
    else:
        print(f"no contact within {config.max_search_time:g} s")
    if result.servos_released:
        print("servos released" + (" through the OE pin" if result.servos_released_by == "oe"
                                   else ""))
    else:
        print("servos NOT confirmed released")


def _oscillator(args) -> float:
    """The PCA9685 oscillator frequency from ``--oscillator-hz`` or ``--measured-pwm-hz``."""
    from ..chips.pca9685 import OSCILLATOR_HZ
    from .pca9685 import oscillator_from_measurement, prescale_for

    if args.oscillator_hz is not None and args.measured_pwm_hz is not None:
        raise ValueError("give --oscillator-hz or --measured-pwm-hz, not both")
    if args.measured_pwm_hz is not None:
        return oscillator_from_measurement(args.measured_pwm_hz, prescale_for(50.0))
    return OSCILLATOR_HZ if args.oscillator_hz is None else float(args.oscillator_hz)
