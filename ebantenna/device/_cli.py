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
        "contact, 1 without one, 3 whenever the servos were not confirmed released, whatever "
        "else happened (an error, a signal, a full disk, a stall): the recording is saved "
        "first, to --out or, when that cannot be written, to acquire-unreleased-PID.npz in the "
        "working or temporary folder, and the last line says to cut the servo supply.",
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
    _simulated_options(parser)
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


def _simulated_options(parser) -> None:
    """The faults and settings of the simulated rig (``--simulated`` only)."""
    parser.add_argument("--inject-faults", type=float, default=0.0, metavar="RATE",
                        help="simulated only: fraction of I2C transfers that fail, every kind "
                        "(no acknowledge, EIO, ETIMEDOUT, EAGAIN, EINTR, late errors, short "
                        "reads, over-reported FIFO counts)")
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
                        help="simulated only: a transfer that times out hangs S seconds first, "
                        "0 to 10 (Linux gives an adapter one second by default)")
    parser.add_argument("--release-fails", action="store_true",
                        help="simulated only: every write that switches the servos off fails")
    parser.add_argument("--slow-host", type=float, nargs=2, metavar=("SHARE", "LONGEST"),
                        help="simulated only: before a SHARE of the transfers (0 to 1) the host "
                        "loses the processor for up to LONGEST seconds (0 to 10)")
    parser.add_argument("--bus-hz", type=float, default=RASPBERRY_PI_BUS_HZ, metavar="HZ",
                        help="simulated only: I2C clock, up to 3.4e6 (the High-speed mode) "
                        "(default 100000, a Raspberry Pi's)")


#: Exit code of ``acquire`` when the servos could not be released (the recording is saved).
EXIT_NOT_RELEASED = 3

#: What to do when the servos could not be released.
CUT_SUPPLY = ("the servos could not be released and may still be powered: switch off the servo "
              "supply (V+ of the PCA9685) now")


def run(args: argparse.Namespace) -> int:
    """Run the acquisition; returns the exit code (0 on contact, 1 without one, 3 whenever the
    servos were not confirmed released, whatever else happened: the recording is then saved
    first, the instruction to cut the servo supply printed last)."""
    from .._validate import check_in_range
    from .pantilt import MAX_DURATION

    ratio = check_in_range("--ratio", args.ratio, 0.0, 1.0)
    check_in_range("--duration", args.duration, 0.0, MAX_DURATION, high_inclusive=True)
    setup = _setup(args, ratio)
    try:
        result = _acquire(args, setup)
    except BaseException as exc:  # noqa: BLE001 - every way out is checked for the servos
        if not _servos_safe(setup):
            return _end_unsafe(args, setup, exc, _result_of(exc))
        raise _released_error(args, setup, exc) from None
    if not _servos_safe(setup):
        return _end_unsafe(args, setup, None, result)
    summary = _summary(args, setup, result)
    if args.json:
        from ..cli import print_json

        print_json(summary)
    else:
        _print_text(summary, result, setup["config"])
    if summary.get("save_failed"):
        raise OSError(f"{summary['save_failed']}; the recording was saved to {summary['out']}"
                      if summary["out"] else summary["save_failed"])
    return 0 if result.contact_detected else 1


def _servos_safe(setup: dict) -> bool:
    """Whether nothing can be driving the servos once the program has exited: the controller
    was never written to, or its servo outputs last read back switched off. The OE pin held
    high does not count: it holds the outputs off only while the program runs (``OE_ONLY``)."""
    unit = setup.get("unit")
    return unit is None or unit.released


def _held_by_oe(setup: dict) -> bool:
    """Whether the OE pin holds every output off now (until the program exits)."""
    oe = setup.get("oe")
    return oe is not None and oe.disabled


def _result_of(exc):
    """The finished result an exception carries (a failed release's), if any."""
    while exc is not None:
        result = getattr(exc, "result", None)
        if result is not None:
            return result
        exc = exc.__context__
    return None


def _released_error(args, setup: dict, exc: BaseException) -> BaseException:
    """The error to end with when the servos are known to be off: a stall or an interrupt saves
    what it kept first."""
    from ..cli import Terminated, interrupted
    from .safety import SignalReceived
    from .watchdog import StreamStalledError

    if isinstance(exc, StreamStalledError):
        return _stalled(exc, setup["out"])
    if isinstance(exc, KeyboardInterrupt | SignalReceived):
        partial = _interrupted_partial(args, setup, exc)
        if isinstance(exc, SignalReceived):  # SIGTERM or SIGHUP, as the servo guard saw it
            exc = Terminated(exc.signum)
        return interrupted(exc, partial)
    return exc


def _kept_recording(setup: dict, exc):
    """What a run that ended without a result kept: the error's recording (a stall's, an
    interrupted window's), else every sample the stream kept, marked ``interrupted``."""
    recording = getattr(exc, "recording", None)
    if recording is not None:
        return recording
    mpu = setup.get("mpu")
    if mpu is None or mpu.stream is None or mpu.samples_read == 0:
        return None
    try:
        return mpu.to_recording(0, mpu.stream_position,
                                metadata={**setup["labels"], "interrupted": True})
    except (ValueError, OSError):
        return None


def _end_unsafe(args, setup: dict, exc: BaseException | None, result) -> int:
    """End a run whose servos were not confirmed released, however it ended: save the recording
    (atomically; a fallback location when ``--out`` cannot be written), say what happened,
    print the instruction to cut the servo supply last, and return 3. Signals are ignored
    meanwhile: the operator must see the instruction."""
    from ..cli import print_json, signals_ignored
    from .oe import OE_ONLY
    from .recording_session import describe_stop, save_recording

    with signals_ignored():
        recording = result.recording if result is not None else _kept_recording(setup, exc)
        saved, failures = (None, []) if recording is None else save_recording(
            recording, setup["out"], fallback_name="acquire-unreleased.npz")
        if result is not None:
            summary = _summary(args, setup, result, saved=(saved, failures))
        else:
            summary = {"mode": "simulated" if args.simulated else "hardware",
                       **setup["labels"], "servos_released": False,
                       "samples": 0 if recording is None else recording.n_samples,
                       "out": None if saved is None else str(saved)}
            if failures:
                summary["save_failed"] = "; ".join(failures)
        if exc is not None:
            summary["error"] = describe_stop(exc)
        summary["action_required"] = CUT_SUPPLY
        summary["servo_outputs_held_by_oe"] = _held_by_oe(setup)
        lines = []
        if exc is not None:
            lines.append(f"ebantenna acquire: {summary['error']}")
        if summary["servo_outputs_held_by_oe"] and OE_ONLY not in summary.get("error", ""):
            lines.append(f"ebantenna acquire: {OE_ONLY}")
        lines += [f"ebantenna acquire: {line}" for line in failures]
        if saved is not None:
            lines.append(f"ebantenna acquire: recording saved to {saved}")
        elif recording is not None:
            lines.append("ebantenna acquire: the recording could not be saved anywhere")
        try:
            if args.json:
                print_json(summary)
            elif result is not None:
                _print_text(summary, result, setup["config"])
            sys.stdout.flush()
        except OSError:
            pass  # stdout gone (a closed pipe): the instruction still goes to stderr
        for line in lines + [f"ebantenna acquire: {CUT_SUPPLY}"]:
            print(line, file=sys.stderr, flush=True)
    return EXIT_NOT_RELEASED


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
        transfer_timeout=args.transfer_timeout, release_fails=args.release_fails,
        slow_host=tuple(args.slow_host or ()))
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
                      "--slow-host": args.slow_host,
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
    """Search and record; returns the result (the servos' state is the unit's, see
    :func:`_servos_safe`). A failed release hands back its finished result in the error."""
    from .mpu6050 import MPU6050
    from .pantilt import PanTilt, search_and_record
    from .pca9685 import PCA9685
    from .safety import ReleaseError

    bus, clock = setup["bus"], setup["clock"]
    try:
        # The servos first: switched off before anything else can fail (a missing
        # accelerometer must not leave them where an earlier run put them).
        setup["unit"] = unit = PanTilt(PCA9685(bus, clock=clock,
                                               oscillator_hz=setup["oscillator"]))
        unit.initialize()
        setup["mpu"] = mpu = MPU6050(bus, clock=clock)
        mpu.initialize()
        return search_and_record(mpu, unit, setup["config"], labels=setup["labels"],
                                 output_enable=setup["oe"])
    except ReleaseError as exc:
        if exc.result is None:
            raise
        return exc.result
    finally:
        bus.close()
        if setup["oe"] is not None and not setup["oe"].disabled:
            setup["oe"].close()  # a line driven high is kept: closed, it would float low


def _stalled(exc, out) -> OSError:
    """The error a stalled stream ends ``acquire`` with (servos released), once its partial
    recording is saved."""
    from .recording_session import save_recording

    saved, failures = (None, []) if exc.recording is None else save_recording(
        exc.recording, out, fallback_name="acquire-partial.npz")
    where = (f"partial recording saved to {saved}" if saved else "nothing to save"
             if exc.recording is None else "the partial recording could not be saved")
    return OSError(f"{exc}; servos released; " + "; ".join([*failures, where]))


def _interrupted_partial(args, setup: dict, exc) -> dict:
    """What an interrupted run kept: search_and_record has released the servos on its way out;
    no recording is complete, but what the window held after a contact is saved, marked."""
    from .recording_session import save_recording

    recording = getattr(exc, "recording", None)
    saved = None if recording is None else save_recording(
        recording, setup["out"], fallback_name="acquire-partial.npz")[0]
    return {"mode": "simulated" if args.simulated else "hardware", **setup["labels"],
            "contact_detected": True if recording is not None else None,
            "samples": None if recording is None else recording.n_samples,
            "out": None if saved is None else str(saved),
            "servos_released": getattr(exc, "servos_released", None)}


def _summary(args, setup: dict, result, saved=None) -> dict:
    """The JSON summary (the command's contract), with the recording saved if asked (always
    when the servos could not be released: nothing made is dropped). ``saved`` is the outcome
    of a save already made, ``(path or None, failures)``."""
    from .recording_session import save_recording

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
    if saved is None and result.recording is not None and (
            out is not None or not result.servos_released):
        saved = save_recording(result.recording, out, fallback_name="acquire-unreleased.npz")
    if saved is not None:
        path, failures = saved
        summary["out"] = None if path is None else str(path)
        if failures:
            summary["save_failed"] = "; ".join(failures)
    if not result.servos_released:
        summary["action_required"] = CUT_SUPPLY
    return summary


def _sole(summary: dict) -> str:
    """The timestamps' uncertainty when no other program reads the FIFO, as a clause."""
    sole = summary.get("timestamp_uncertainty_sole_reader_s")
    return "" if sole is None else f" ({1e6 * sole:.0f} us if no other program reads the FIFO)"


def _print_text(summary: dict, result, config) -> None:
    """The human-readable report."""
    if result.contact_detected:
        print(f"contact after {result.contact_time:.3f} s at pan/tilt "
              f"{result.contact_angles[0]:.1f}/{result.contact_angles[1]:.1f} deg; "
              f"servos {'stopped' if result.servos_stopped else 'NOT confirmed stopped'}")
        print(f"recorded {result.samples} samples at {result.recording.fs:.2f} Hz "
              f"(estimated), {result.samples_lost} lost, {result.i2c_retries} I2C retries, "
              f"{summary['fifo_restarts']} FIFO restarts, {summary['fifo_counts_rejected']} "
              f"FIFO counts rejected, {summary['samples_discarded']} samples read and "
              f"discarded; timestamps within "
              f"{1e6 * summary['timestamp_uncertainty_s']:.0f} us{_sole(summary)}")
        if summary["out"]:
            print(f"saved {summary['out']}")
        for warning in result.warnings():
            print(f"warning: {warning}")
    else:
        print(f"no contact within {config.max_search_time:g} s")
    if result.servos_released:
        print("servos released")
    else:
        print("servos NOT confirmed released" + (
            " (their outputs held off by the OE pin until this program exits)"
            if result.servos_released_by == "oe" else ""))


def _oscillator(args) -> float:
    """The PCA9685 oscillator frequency from ``--oscillator-hz`` or ``--measured-pwm-hz``."""
    from ..chips.pca9685 import OSCILLATOR_HZ
    from .pca9685 import oscillator_from_measurement, prescale_for

    if args.oscillator_hz is not None and args.measured_pwm_hz is not None:
        raise ValueError("give --oscillator-hz or --measured-pwm-hz, not both")
    if args.measured_pwm_hz is not None:
        return oscillator_from_measurement(args.measured_pwm_hz, prescale_for(50.0))
    return OSCILLATOR_HZ if args.oscillator_hz is None else float(args.oscillator_hz)
