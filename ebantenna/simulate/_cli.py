"""``ebantenna simulate``: one simulated recording (``ebantenna dataset`` is in ``paper``)."""

from __future__ import annotations


def _hinge(value: str):
    if value in ("clamped", "pinned"):
        return value
    try:
        return float(value)
    except ValueError:
        raise ValueError(
            f"--hinge must be clamped, pinned or a rotational stiffness in N m/rad, got {value!r}"
        ) from None


def register(subparsers) -> None:
    """Add the ``simulate`` command."""
    from ..cli import seed_argument

    sim = subparsers.add_parser(
        "simulate",
        help="simulate one recording of the tip accelerometer",
        description="Simulate the tip accelerations after the probe hits an object, from a "
        "built-in scene (ideal, paper) or a scene file (.toml/.json), and save them as .npz.",
    )
    sim.add_argument("--scene", required=True, metavar="NAME|FILE", help="ideal, paper or a file")
    where = sim.add_mutually_exclusive_group()
    where.add_argument("--ratio", type=float, metavar="A", help="contact at A * L from the hinge")
    where.add_argument("--contact", type=float, metavar="M", help="contact position (m)")
    sim.add_argument("--hinge", metavar="clamped|pinned|K", help="hinge (or rotational spring)")
    sim.add_argument("--material", metavar="NAME", help="touched material")
    sim.add_argument(
        "--seed",
        type=seed_argument,
        default=0,
        metavar="S",
        help="seed of random effects, 0 ... 2**63 - 1 (0)",
    )
    sim.add_argument("--out", required=True, metavar="FILE.npz", help="where to save the recording")
    sim.add_argument("--json", action="store_true", help="print one JSON object")
    sim.set_defaults(func=run_simulate)


def run_simulate(args) -> int:
    """Run ``ebantenna simulate``."""
    from .._validate import output_path
    from ..cli import print_json
    from .scene import resolve_scene
    from .simulator import simulate

    out = output_path("--out", args.out, ".npz")  # refused before any work is done
    scene = resolve_scene(args.scene)
    changes = {}
    if args.ratio is not None:
        if not 0 < args.ratio < 1:
            raise ValueError(f"--ratio must lie in (0, 1), got {args.ratio!r}")
        changes["contact"] = args.ratio * scene.probe.length
    elif args.contact is not None:
        changes["contact"] = args.contact
    if args.hinge is not None:
        changes["hinge"] = _hinge(args.hinge)
    if args.material is not None:
        changes["material"] = args.material
    if changes:
        scene = scene.with_(**changes)
    rec = simulate(scene, seed=args.seed)
    out = rec.save(out)
    summary = {
        "scene": scene.name,
        "contact": scene.contact,
        "hinge": scene.hinge,
        "material": scene.material,
        "seed": args.seed,
        "effects": list(scene.effect_names),
        "fs": rec.fs,
        "samples": rec.n_samples,
        "modes_x_hz": rec.metadata["modes_x_hz"],
        "modes_z_hz": rec.metadata["modes_z_hz"],
        "out": str(out),
    }
    if args.json:
        print_json(summary)
        return 0
    print(
        f"Scene {scene.name}: {scene.material} touched at {100 * scene.contact:.2f} cm, "
        f"{rec.n_samples} samples at {rec.fs:g} Hz -> {out}"
    )
    print(f"  X modes (Hz): {', '.join(f'{f:.2f}' for f in summary['modes_x_hz'])}")
    print(f"  Z modes (Hz): {', '.join(f'{f:.2f}' for f in summary['modes_z_hz'])}")
    return 0
