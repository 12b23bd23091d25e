"""``ebantenna acquire``: search for an object, stop on contact and record the vibration."""

from __future__ import annotations

import argparse


def register(subparsers) -> None:
    """Add the ``acquire`` subcommand."""
    parser = subparsers.add_parser(
        "acquire",
        help="sweep the probe until it touches something, then record the vibration",
        description="Run the pan-tilt search of the paper (Figs. 7-8): sweep an elliptical path, "
        "stop the servos when the accelerometer reports a contact, record the vibration window "
        "and release the servos. --simulated runs on a simulated I2C bus (the scene simulator "
        "provides the vibration); --bus N drives the real rig on /dev/i2c-N.",
    )
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--simulated", action="store_true", help="use the simulated rig")
    where.add_argument("--bus", type=int, metavar="N", help="I2C bus number of the real rig")
    parser.add_argument("--material", default="brass",
                        help="touched material (simulated: what is simulated; hardware: a label)")
    parser.add_argument("--ratio", type=float, default=0.5,
                        help="contact distance over probe length, in (0, 1) (default 0.5)")
    parser.add_argument("--scene", default="paper", help="built-in scene for --simulated")
    parser.add_argument("--seed", type=int, default=0, help="seed of the simulation")
    parser.add_argument("--inject-faults", type=float, default=0.0, metavar="RATE",
                        help="simulated only: fraction of I2C transfers that fail (errno 121)")
    parser.add_argument("--threshold", type=float, default=2.0,
                        help="contact threshold on the acceleration change, m/s^2 (default 2)")
    parser.add_argument("--duration", type=float, default=1.0,
                        help="recorded time after the contact, s (default 1)")
    parser.add_argument("--out", metavar="FILE.npz", help="save the recording here")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run the acquisition; returns the exit code (0 on contact, 1 without one)."""
    from .._validate import check_in_range
    from ..probe import material as lookup_material
    from .mpu6050 import MPU6050
    from .pantilt import PanTilt, SearchConfig, search_and_record
    from .pca9685 import PCA9685

    ratio = check_in_range("ratio", args.ratio, 0.0, 1.0)
    material = lookup_material(args.material).name
    config = SearchConfig(threshold=args.threshold, duration=args.duration)
    labels = {"material": material, "ratio": ratio}
    if args.simulated:
        from .simulated import Faults, SimulatedRig

        rig = SimulatedRig.for_contact(scene=args.scene, material=material, ratio=ratio,
                                       seed=args.seed,
                                       faults=Faults(error_rate=args.inject_faults))
        bus, clock = rig.bus, rig.clock
        labels.update({"scene": args.scene, "seed": args.seed, "simulated": True})
    else:
        if args.inject_faults:
            raise ValueError("--inject-faults works only with --simulated")
        from smbus2 import SMBus

        from .clock import SystemClock

        bus, clock = SMBus(args.bus), SystemClock()
        labels.update({"bus": args.bus, "simulated": False})
    try:
        mpu = MPU6050(bus, clock=clock)
        mpu.initialize()
        unit = PanTilt(PCA9685(bus, clock=clock))
        unit.initialize()
        result = search_and_record(mpu, unit, config, labels=labels)
    finally:
        bus.close()
    summary = {"mode": "simulated" if args.simulated else "hardware", **labels,
               **result.summary(), "out": None}
    if args.simulated:
        summary["i2c_errors_injected"] = rig.bus.errors_injected
    if args.out and result.recording is not None:
        summary["out"] = str(result.recording.save(args.out))
    if args.json:
        from ..cli import print_json

        print_json(summary)
    else:
        if result.contact_detected:
            print(f"contact after {result.contact_time:.3f} s at pan/tilt "
                  f"{result.contact_angles[0]:.1f}/{result.contact_angles[1]:.1f} deg; "
                  f"servos {'stopped' if result.servos_stopped else 'NOT confirmed stopped'}")
            print(f"recorded {result.samples} samples at {result.recording.fs:g} Hz, "
                  f"{result.samples_lost} lost, {result.i2c_retries} I2C retries")
            if summary["out"]:
                print(f"saved {summary['out']}")
        else:
            print(f"no contact within {config.max_search_time:g} s; servos released")
    return 0 if result.contact_detected else 1
