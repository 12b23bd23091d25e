"""``ebantenna record``, ``ebantenna dataset --from-recordings`` and ``ebantenna reproduce --data``:
from the rig to the report."""

from __future__ import annotations

import math
import os
import sys
import time

#: Exit code of ``record`` when the servos may still be powered (as ``acquire``'s).
EXIT_SERVOS_POWERED = 3
#: ``record``'s default limit of the share of a window lost to bus faults (a share, not a number
#: of failures): a failed FIFO read restarts the FIFO and costs 4 to 7 % of a one-second window
#: at 100 kHz, under 3 % at 400 kHz, and two about twice that (measured on the simulated bus:
#: the user guide's "Recording your own data set").


def register(subparsers) -> None:
    """Add the ``record`` and ``calibrate`` commands."""
    _add_record(subparsers)
    _add_calibrate(subparsers)


def _share(text: str) -> float:
    """The type of ``--inject-faults`` and ``--max-lost``: a share in [0, 1)."""
    import argparse

    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number in [0, 1), got {text!r:.40}") from None
    if not 0.0 <= value < 1.0:  # NaN fails too
        raise argparse.ArgumentTypeError(f"must be a number in [0, 1), got {text:.40}")
    return value


def _attempts(text: str) -> int:
    """The type of ``--attempts``: 1 to the I2C layer's own bound on retries."""
    import argparse

    from ...device.i2c import MAX_ATTEMPTS

    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number, got {text!r:.40}") from None
    if not 1 <= value <= MAX_ATTEMPTS:
        raise argparse.ArgumentTypeError(f"must lie in [1, {MAX_ATTEMPTS}], got {text:.40}")
    return value


def _add_record(subparsers) -> None:
    """The ``record`` command."""
    from ...cli import seed_argument
    from ...device._cli import device_number
    from ...device.recording_session import MAX_LOST

    rec = subparsers.add_parser(
        "record",
        help="record a whole data set on the rig: the paper's protocol or a plan file",
        description="Walk the operator through the touches of the paper's protocol (5 materials "
        "x every 5 mm x 25 repetitions), of its quick version, or of a plan file: for each "
        "touch search, touch, stop, record and release, and save the recording with its labels "
        "and the rig's account in DIR, with a manifest (DIR/session.json) holding every file's "
        "checksum. Run the same command again to resume after any stop: nothing is recorded "
        "twice and nothing saved is lost; --dry-run shows the plan, its time estimate and the "
        "touches done and missing without moving anything. Exit codes: 0 every touch saved (or "
        "the dry run printed); 1 a search found no contact (place the object, run again); 2 bad "
        "input, or the session stopped safely: the accelerometer does not answer once the servo "
        "outputs read back off, or a touch lost too many samples on every attempt (the message "
        "says which); 3 the servos may still be powered (cut their supply): the bus or the "
        "servo board does not answer, or the outputs do not read back off; 130 and 143 on "
        "Ctrl-C and SIGTERM.",
    )
    where = rec.add_mutually_exclusive_group(required=True)
    where.add_argument("--simulated", action="store_true", help="use the simulated rig")
    where.add_argument("--bus", type=device_number, metavar="N",
                       help="I2C bus number of the real rig")
    rec.add_argument("--out", required=True, metavar="DIR", help="the session folder")
    what = rec.add_mutually_exclusive_group()
    what.add_argument("--plan", metavar="FILE", help="a plan file (.toml or .json)")
    what.add_argument("--quick", action="store_true",
                      help="the quick design (every 5 cm, 3 repetitions) instead of the paper's")
    rec.add_argument("--scene", default="paper", metavar="NAME|FILE",
                     help="simulated only: the scene every touch is simulated in (paper)")
    rec.add_argument("--seed", type=seed_argument, default=0,
                     help="simulated only: seed of the design's variation and the faults (0)")
    rec.add_argument("--inject-faults", type=_share, default=0.0, metavar="RATE",
                     help="simulated only: fraction of I2C transfers that fail, every kind")
    rec.add_argument("--oe-gpio", type=device_number, metavar="PIN",
                     help="hardware only: BCM GPIO wired to the PCA9685's OE pin")
    rec.add_argument("--max-lost", type=_share, default=MAX_LOST, metavar="F",
                     help="a touch whose window lost more than this share is made again; kept "
                     "in the session, and 'dataset --from-recordings' holds its recordings to "
                     f"the same limit ({MAX_LOST:g}, a share of the window: one failed FIFO "
                     "read costs 4-7 %% of a one-second window at 100 kHz (a touch with one is "
                     "sometimes made again) and under 3 %% at 400 kHz; two about twice that)")
    rec.add_argument("--attempts", type=_attempts, default=5, metavar="N",
                     help="tries of a touch that lost too much before the session stops, 1 to "
                     "100 (5)")
    rec.add_argument("--no-wait", action="store_true",
                     help="hardware only: do not wait for Enter when the object is to be moved")
    rec.add_argument("--yes", action="store_true",
                     help="start a session expected to take over an hour on the rig (without "
                     "it, such a plan is refused with its estimate)")
    rec.add_argument("--dry-run", action="store_true",
                     help="print the plan, its time estimate and the touches already done and "
                     "still missing; move nothing, write nothing")
    rec.add_argument("--json", action="store_true", help="print one JSON object")
    rec.set_defaults(func=run_record)


def _add_calibrate(subparsers) -> None:
    """The ``calibrate`` command."""
    cal = subparsers.add_parser(
        "calibrate",
        help="fit the hinge stiffness, tip mass and loss factor to recordings",
        description="Fit the probe's hinge stiffness, tip mass and loss factor to a data set of "
        "recordings at known contact distances (e.g. from 'ebantenna dataset "
        "--from-recordings') with the scene's own model (the touched rod's modes included when "
        "the scene has them), each with its 95 % interval; a parameter the recordings do not "
        "determine is reported as not identifiable, with the reason and a warning. Writes the "
        "scene with the fitted values (usable by 'ebantenna simulate --scene FILE'), a figure "
        "of measured against modelled frequency versus distance, and calibration.json in --out.",
    )
    cal.add_argument("--data", required=True, metavar="FILE", help="the data set of recordings")
    cal.add_argument("--scene", default="paper", metavar="NAME|FILE",
                     help="the scene to calibrate (paper)")
    cal.add_argument("--out", required=True, metavar="DIR", help="output directory")
    cal.add_argument("--json", action="store_true", help="print one JSON object")
    cal.set_defaults(func=run_calibrate)


def run_calibrate(args) -> int:
    """Run ``ebantenna calibrate``."""
    import json
    import warnings
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    from ..._validate import check_path, output_dir, output_file_in
    from ...cli import print_json
    from ...simulate import load_dataset
    from ...simulate.scene import resolve_scene
    from .calibration import (
        IdentifiabilityWarning,
        ModelMisfitWarning,
        calibrate,
        plot_calibration,
    )

    output_dir("--out", args.out)  # refused before any work is done
    base = resolve_scene(args.scene)
    for name in (f"{base.name}-calibrated.toml", "calibration.png", "calibration.json"):
        output_file_in("--out", args.out, name)  # what is written there, at the end
    data = load_dataset(check_path("--data", args.data))
    with warnings.catch_warnings():
        for said_below in (IdentifiabilityWarning, ModelMisfitWarning):  # once each
            warnings.simplefilter("ignore", said_below)
        cal = calibrate(data, base)
    for name, why in cal.not_identifiable.items():
        print(f"ebantenna calibrate: warning: {name} is not identifiable from these recordings: "
              f"{why}", file=sys.stderr)
    if cal.misses_recordings:
        print(f"ebantenna calibrate: warning: {cal.fit_statement}", file=sys.stderr)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scene = cal.scene(base)
    summary = {**cal.to_dict(), "data": str(args.data),
               "scene": str(scene.save(out / f"{scene.name}.toml"))}
    fig = plot_calibration(cal, base)
    fig.savefig(out / "calibration.png", dpi=120)
    summary["figure"] = str(out / "calibration.png")
    (out / "calibration.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    if args.json:
        print_json(summary)
        return 0
    _print_calibration(cal, summary)
    return 0


def _print_calibration(cal, summary) -> None:
    """The calibration as ``calibrate`` prints it: the fit, each parameter, the scene."""
    from .calibration import PARAMETERS

    units = {"hinge_stiffness": "N m/rad", "tip_mass": "kg", "loss_factor": ""}
    print(f"model: {cal.model}; {summary['contact_materials']} contacts fitted (each distance "
          f"and material, at {summary['distances']} distances), rms misfit "
          f"{cal.rms_residual_hz:.3g} Hz; {cal.fit_statement}")
    for position, why in cal.left_out.items():
        print(f"left out of the fit: {position}: {why}")
    for name in PARAMETERS:
        lo, hi = cal.interval(name)
        if name in cal.not_identifiable:
            bound = (f"at least {lo:.4g} {units[name]}".rstrip() if lo > 0 and math.isinf(hi)
                     else f"at most {hi:.4g} {units[name]}".rstrip() if math.isfinite(hi)
                     else "no bound")
            print(f"{name}: not identifiable ({bound}; see the warning)")
        else:
            print(f"{name}: {getattr(cal, name):.4g} {units[name]} (95 % {lo:.4g} - {hi:.4g})"
                  .replace("  (", " ("))
    print(f"scene written to {summary['scene']}")
    if cal.held_at_fit_stop:
        print(f"(the scene holds the fit's stopping point for "
              f"{' and '.join(cal.held_at_fit_stop)}, which the recordings do not determine: not "
              "an estimate)")


def _plan_of(args):
    """The plan, and the scene of a simulated rig (None on hardware)."""
    from ...device.plan import load_plan
    from ...simulate.scene import resolve_scene
    from .planning import protocol_plan

    scene = resolve_scene(args.scene) if args.simulated else None
    if args.plan is not None:
        return load_plan(args.plan), scene
    return protocol_plan(quick=args.quick, scene=scene, seed=args.seed), scene


def _plan_and_connect(args):
    """The plan, the ``connect`` of the rig, and the rig's description."""
    plan, scene = _plan_of(args)
    if args.simulated:
        if abs(scene.probe.length - plan.probe_length) > 1e-9:
            raise ValueError(f"the plan's probe is {plan.probe_length:g} m long, the scene's "
                             f"{scene.probe.length:g} m")
        return plan, *_simulated(args, scene)
    return plan, *_hardware(args)


def _simulated(args, scene):
    from ...device.simulated import Faults
    from ...device.simulated.touches import simulated_connect
    from ...simulate import simulate

    if args.oe_gpio is not None or args.no_wait:
        raise ValueError("--oe-gpio and --no-wait work only on the real rig (--bus)")
    faults = Faults.every_kind(args.inject_faults) if args.inject_faults else None
    rig = {"simulated": True, "scene": scene.name, "seed": args.seed,
           "inject_faults": args.inject_faults}
    return simulated_connect(scene, simulate, faults=faults, seed=args.seed), rig, None


def _hardware(args):
    from ...device.clock import SystemClock
    from ...device.oe import OutputEnable
    from ...device.recording_session import Connection

    if args.inject_faults or args.seed or args.scene != "paper":
        raise ValueError("--inject-faults, --seed and --scene work only with --simulated")
    if not os.path.exists(f"/dev/i2c-{args.bus}"):
        raise FileNotFoundError(f"/dev/i2c-{args.bus} does not exist: no I2C bus {args.bus} on "
                                "this machine (see 'ebantenna acquire --help' and the hardware "
                                "page to enable I2C)")

    def connect(touch, attempt):
        from smbus2 import SMBus

        oe = None if args.oe_gpio is None else OutputEnable.gpio(args.oe_gpio)
        return Connection(SMBus(args.bus), SystemClock(), oe)

    def confirm(text):
        if not args.no_wait:
            input(f"{text}, then press Enter ")

    return connect, {"simulated": False, "bus": args.bus, "oe_gpio": args.oe_gpio}, confirm


def run_record(args) -> int:
    """Run ``ebantenna record``."""
    from ...cli import Terminated, interrupted, print_json
    from ...device.recording_session import NoContactError, RecordingSession, UnsafeRigError
    from ...device.safety import SignalReceived

    if not args.out:
        raise ValueError("--out must name the session folder, got an empty path (it would "
                         "record into the working directory)")
    if args.dry_run:
        return _dry_run(args)
    plan, connect, rig, confirm = _plan_and_connect(args)
    from ...device.plan import check_session_length

    check_session_length(plan, agreed=args.yes)
    session = RecordingSession(
        args.out, plan, connect, rig=rig, max_lost=args.max_lost, attempts=args.attempts,
        confirm=confirm,
        say=_status_line,
        show_progress=False if args.json else None)
    start = time.perf_counter()
    code, stopped = 0, None
    try:
        session.open()
        session.run()
    except NoContactError as exc:
        code, stopped = 1, str(exc)
    except UnsafeRigError as exc:
        code, stopped = (EXIT_SERVOS_POWERED if exc.servos_may_be_powered else 2), str(exc)
    except BaseException as exc:  # noqa: BLE001 - the servos decide the exit code first
        if session.servos_may_be_powered:  # whatever else happened: exit 3, the instruction
            code, stopped = EXIT_SERVOS_POWERED, _unsafe_stop(session, exc)
        elif isinstance(exc, KeyboardInterrupt | SignalReceived):
            if isinstance(exc, SignalReceived):
                exc = Terminated(exc.signum)
            raise interrupted(exc, _summary(args, session, start)) from None
        else:
            raise
    if code == EXIT_SERVOS_POWERED:
        from ...cli import signals_ignored

        with signals_ignored():  # the instruction must reach the operator
            summary = _summary(args, session, start)
            summary["stopped"] = stopped
            if args.json:
                print_json(summary)
            print(f"ebantenna record: stopped: {stopped}", file=sys.stderr, flush=True)
        return code
    summary = _summary(args, session, start)
    if stopped:
        summary["stopped"] = stopped
        print(f"ebantenna record: stopped: {stopped}", file=sys.stderr)
    if args.json:
        print_json(summary)
    elif not stopped:
        print(f"saved {summary['saved']} of {summary['touches']} touches in {args.out} "
              f"({summary['retakes']} made again); manifest {summary['manifest']}")
    return code


def _unsafe_stop(session, exc: BaseException) -> str:
    """Why a run whose servos may be powered stopped, with the instruction, recorded in the
    manifest (when it can be written) so that the next run checks the rig first."""
    from ...device.recording_session import CUT_SUPPLY, describe_stop

    why = f"{describe_stop(exc)}; the servos were not confirmed released: {CUT_SUPPLY}"
    unsafe = (session.manifest or {}).get("unsafe")
    if not unsafe:
        session.mark_unsafe(why)
    return why


def _status_line(text: str) -> None:
    """One status line on stderr, written above the progress bar (not onto its line)."""
    import tqdm.std

    tqdm.std.tqdm.write(f"ebantenna record: {text}", file=sys.stderr)


def _summary(args, session, start) -> dict:
    manifest = session.manifest or {"recordings": {}, "retakes": []}
    released = [e.get("servos_released") for e in manifest["recordings"].values()]
    return {"out": str(args.out), "plan": session.plan.name, "touches": len(session.plan),
            "saved": len(manifest["recordings"]), "retakes": len(manifest["retakes"]),
            # every saved touch's release read back; False when one is not (or none was saved)
            "servos_released": bool(released) and all(r is True for r in released),
            "manifest": str(session.manifest_path),
            "seconds": round(time.perf_counter() - start, 3)}


def _dry_run(args) -> int:
    """``record --dry-run``: the plan, its time estimate, the touches done and missing."""
    from pathlib import Path

    from ...cli import print_json
    from ...device.plan import plan_differences, session_time
    from ...device.recording_session import MANIFEST, read_manifest

    plan = _plan_of(args)[0]
    path = Path(args.out) / MANIFEST
    done = set()
    if path.exists():
        manifest = read_manifest(path)
        if manifest["plan"] != plan.to_dict():
            differs = "; ".join(plan_differences(manifest["plan"], plan.to_dict()))
            raise ValueError(f"{args.out} holds a session of another plan "
                             f"({manifest['plan']['name']!r}), which differs in {differs}")
        done = {k for k, e in manifest["recordings"].items()
                if (Path(args.out) / e["file"]).exists()}
    missing = [t for t in plan if t.key not in done]
    whole, left = session_time(plan), _time_of(plan, missing)
    summary = {"out": str(args.out), "plan": plan.name, "touches": len(plan),
               "materials": list(plan.materials), "contacts_m": list(plan.contacts),
               "repetitions": plan.repetitions, "done": len(plan) - len(missing),
               "missing": len(missing), "missing_touches": [t.key for t in missing],
               "estimate_s": whole["total_s"], "estimate_worst_s": whole["worst_s"],
               "remaining_s": left[0], "remaining_worst_s": left[1], "dry_run": True}
    if args.json:
        print_json(summary)
        return 0
    print(f"plan {plan.name!r}: {len(plan.materials)} materials x {len(plan.contacts)} contacts "
          f"x {plan.repetitions} repetitions = {len(plan)} touches; about "
          f"{whole['total_s'] / 60:.0f} min ({whole['worst_s'] / 60:.0f} min if every search "
          "takes its longest)")
    print(f"done {summary['done']}, missing {len(missing)} (about {left[0] / 60:.0f} min)")
    for key in summary["missing_touches"][:10]:
        print(f"  {key}")
    if len(missing) > 10:
        print(f"  ... and {len(missing) - 10} more")
    return 0


def _time_of(plan, touches) -> tuple[float, float]:
    """Average and worst seconds of ``touches`` of ``plan`` (each placement counted once)."""
    from ...device.plan import MOVE_SECONDS, session_time

    if not touches:
        return 0.0, 0.0
    per = session_time(plan)
    placements = len({(t.material, t.contact) for t in touches})
    return (len(touches) * per["touch_s"] + placements * MOVE_SECONDS,
            len(touches) * per["touch_worst_s"] + placements * MOVE_SECONDS)


def add_from_recordings(parser) -> None:
    """The ``--from-recordings`` option of ``ebantenna dataset``."""
    parser.add_argument("--from-recordings", metavar="DIR",
                        help="assemble the recordings of a session (ebantenna record) into a "
                        "data set in --out instead of simulating one")


def run_from_recordings(args) -> int:
    """``ebantenna dataset --from-recordings DIR``."""
    from ..._validate import output_file_in
    from ...cli import print_json
    from .assemble import assemble_dataset

    if args.quick:
        raise ValueError("--quick builds the simulated data set; not with --from-recordings")
    from ...device.recording_session import MANIFEST, UNRECORDED_MAX_LOST, read_manifest

    manifest = read_manifest(os.path.join(args.from_recordings, MANIFEST))
    plan = manifest["plan"]
    output_file_in("--out", args.out, f"recorded-{plan['name']}.npz", renamed=True)  # first
    touches = len(plan["materials"]) * len(plan["contacts_m"]) * plan["repetitions"]
    saved = len(manifest["recordings"])
    if saved < touches:
        print(f"ebantenna dataset: warning: the session is not finished: {saved} of {touches} "
              f"touches saved; the data set holds those (run 'ebantenna record' with the same "
              "settings to make the rest)", file=sys.stderr)
    start = time.perf_counter()
    data = assemble_dataset(args.from_recordings, args.out)
    summary = {"path": str(data.path), "signals": data.n_signals, "samples": data.n_samples,
               "fs": data.fs, "materials": sorted({str(m) for m in data.material}),
               "source": "recordings", "session": data.metadata["provenance"]["session"],
               "samples_interpolated": int(sum(data.metadata["provenance"]
                                               ["samples_interpolated"])),
               "recordings_flagged": data.metadata["provenance"]["recordings_flagged"],
               "checksum_sha256": data.metadata["checksum_sha256"],
               "touches_planned": touches, "complete": saved == touches,
               "max_lost": manifest.get("max_lost", UNRECORDED_MAX_LOST),
               "seconds": round(time.perf_counter() - start, 3)}
    if args.json:
        print_json(summary)
    else:
        print(f"{summary['signals']} recordings of {summary['samples']} samples at "
              f"{data.fs:g} Hz assembled into {data.path}")
    if summary["recordings_flagged"]:
        print(f"ebantenna dataset: warning: {summary['recordings_flagged']} of the recordings "
              "carry the driver's flags (suspect timestamps, a clock beyond its tolerance or the "
              "sensor's check), listed under provenance.flags", file=sys.stderr)
    return 0


def add_data(parser) -> None:
    """The ``--data`` option of ``ebantenna reproduce``."""
    parser.add_argument("--data", metavar="FILE",
                        help="run the sections that need only recordings on this data set (e.g. "
                        "one assembled by 'ebantenna dataset --from-recordings'); the others are "
                        "reported as not applicable")


def run_data(args) -> int:
    """``ebantenna reproduce --data FILE``."""
    from ..._validate import check_path
    from ...cli import interrupted, print_json
    from ...paper.uncertainty import percent, span
    from .study import reproduce_recorded

    if args.quick or args.cache:
        raise ValueError("--quick and --cache choose the simulated data set; not with --data")
    check_path("--data", args.data)  # refused by its name before any work
    try:
        summary = reproduce_recorded(
            args.data, args.out, seed=args.seed, n_jobs=args.jobs,
            show_progress=None if not args.json else False,
            say=lambda text: print(f"ebantenna reproduce: {text}", file=sys.stderr, flush=True))
    except KeyboardInterrupt as exc:
        raise interrupted(exc, {"out": None, "data": args.data}) from None
    if args.json:
        print_json(summary)
        return 0
    found = summary["intervals"]
    print(f"Study on {summary['data']['path']} ({summary['data']['source']}) written to "
          f"{args.out}/; report {summary['report']['html']}")
    for name in ("svm", "ann") if found else ():
        f = found[name]
        print(f"  {name.upper()} material accuracy: test {percent(f['test_accuracy'])} "
              f"(95 % {span(f['interval95'])} on {f['n_units']} {f['unit']}s; "
              f"{f['n_test']} recordings)")
    print(f"  not applicable: {', '.join(summary['not_applicable'])}")
    return 0
