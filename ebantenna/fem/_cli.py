"""``ebantenna modes`` and ``ebantenna exact``: natural frequencies of the probe."""

from __future__ import annotations

import argparse


def _add_common(parser: argparse.ArgumentParser) -> None:
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--ratio", type=float, metavar="A", help="contact at A * L from the hinge")
    where.add_argument("--contact", type=float, metavar="METRES", help="contact position (m)")
    where.add_argument("--no-contact", action="store_true", help="a probe that touches nothing")
    parser.add_argument(
        "--hinge", default="clamped", choices=("clamped", "pinned"), help="hinge condition"
    )
    parser.add_argument("--modes", type=int, default=3, metavar="K", help="number of modes (3)")
    parser.add_argument(
        "--tip-mass", type=float, default=0.0, metavar="KG", help="point mass at the tip (kg)"
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def register(subparsers) -> None:
    """Add the ``modes`` and ``exact`` commands."""
    modes = subparsers.add_parser(
        "modes",
        help="natural frequencies and mode shapes by finite elements",
        description="Natural frequencies of the probe by Euler-Bernoulli beam elements.",
    )
    _add_common(modes)
    modes.add_argument(
        "--elements", type=int, default=64, metavar="N", help="number of elements (2 = the paper's)"
    )
    modes.add_argument("--plot", metavar="FILE", help="save the mode shapes as an image")
    modes.set_defaults(func=run_modes)
    exact = subparsers.add_parser(
        "exact",
        help="natural frequencies from the exact frequency equation",
        description="Exact natural frequencies of the probe pinned at the contact.",
    )
    _add_common(exact)
    exact.set_defaults(func=run_exact)


def _setup(args):
    from ..probe import Probe

    probe = Probe(tip_mass=args.tip_mass)
    if args.no_contact:
        contact = None
    elif args.ratio is not None:
        if not 0 < args.ratio < 1:
            raise ValueError(f"--ratio must lie in (0, 1), got {args.ratio!r}")
        contact = args.ratio * probe.length
    else:
        contact = args.contact
    return probe, contact


def _report(args, probe, contact, elements, frequencies) -> int:
    from ..cli import print_json

    summary = {
        "probe": probe.summary(),
        "hinge": args.hinge,
        "contact": contact,
        "elements": elements,
        "frequencies_hz": [float(f) for f in frequencies],
    }
    if args.json:
        print_json(summary)
        return 0
    where = "no contact" if contact is None else f"contact at {100 * contact:.2f} cm"
    how = "exact" if elements is None else f"{elements} elements"
    print(f"Probe L = {100 * probe.length:g} cm, hinge {args.hinge}, {where}, {how}:")
    for k, f in enumerate(frequencies, start=1):
        print(f"  mode {k}: {f:12.6f} Hz")
    return 0


def run_modes(args) -> int:
    """Run ``ebantenna modes``."""
    from .._validate import output_path
    from . import Supports, modal_analysis

    plot = None if args.plot is None else output_path("--plot", args.plot, ".png", any_suffix=True)
    probe, contact = _setup(args)
    result = modal_analysis(
        probe,
        Supports(contact=contact, hinge=args.hinge),
        n_elements=args.elements,
        n_modes=args.modes,
    )
    if plot is not None:
        import matplotlib

        matplotlib.use("Agg")
        ax = result.plot()
        ax.set_title(f"Mode shapes, {args.elements} elements")
        ax.figure.tight_layout()
        ax.figure.savefig(plot, dpi=150)
    code = _report(args, probe, contact, args.elements, result.frequencies)
    if plot is not None and not args.json:
        print(f"mode shapes saved to {plot}")
    return code


def run_exact(args) -> int:
    """Run ``ebantenna exact``."""
    from .exact import exact_frequencies

    probe, contact = _setup(args)
    frequencies = exact_frequencies(probe, contact, hinge=args.hinge, n_modes=args.modes)
    return _report(args, probe, contact, None, frequencies)
