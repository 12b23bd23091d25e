"""Effects of the touched object: its own modes, its own damping, the preload's scatter, a contact
that only pushes, friction along it.

:class:`ObjectModes` makes the touched object a vibrating body (a rod in a stand, coupled to the
probe through the contact spring); :class:`ObjectDamping` gives that rod its material's loss
factor; :class:`PreloadScatter` varies how hard the probe presses on it from strike to strike;
:class:`UnilateralContact` lets the probe lift off the rod and strike it again;
:class:`CoulombFriction` holds the probe's motion along the rod by dry friction. The
object's geometry is an assumption of the scene, stated here once: the paper names
five materials ("a brass rod", its Fig. 1) and gives no dimensions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..._validate import check_choice, check_int, check_nonnegative, check_positive
from ...fem.coupling import ROD_DIAMETER, ROD_FREE_LENGTH, Rod
from ...probe import Material, Probe
from ..contact import PRELOAD, tube_on_rod_spring, tube_on_rod_stiffness
from ..stick_slip import check_coefficients
from ..unilateral import MARCHES
from ._base import Effect, check_bodies, check_rng


@dataclass(frozen=True)
class ObjectModes(Effect):
    """The touched object as a rod with its own modes, coupled to the probe by the contact spring.

    The object is a solid round rod clamped upright in a stand
    (:class:`~ebantenna.fem.coupling.Rod`), touched at ``contact_height`` above the clamp. Probe and
    rod are modelled with the same Euler-Bernoulli elements, reduced each on its own by
    Craig-Bampton component-mode synthesis and joined through the contact spring
    (:func:`ebantenna.fem.coupling.coupled_modes`; the witness is
    :func:`ebantenna.fem.coupling.monolithic_modes`, one FEM system of both bodies).
    The spring is the tube pressed on the rod at ``preload``: Hertz contact of crossed cylinders
    in series with the tube wall's ring compliance, wood indented across its grain
    (:func:`ebantenna.simulate.contact.tube_on_rod_stiffness`).

    What the probe then feels of the object is its point mobility: the rod's stiffness, its mass
    and its resonances, which differ from material to material (for the default rod the first
    bending mode in the stand lies at 39 Hz for PVC, 94 Hz for brass and 137 Hz for steel).
    Without this effect the object is rigid (or, with ``contact_compliance``, a rigid body behind
    a spring).

    **Assumptions** (the paper gives no geometry): a rod of ``diameter`` 12 mm, ``free_length``
    250 mm above the stand's clamp (:data:`~ebantenna.fem.coupling.ROD_DIAMETER`,
    :data:`~ebantenna.fem.coupling.ROD_FREE_LENGTH`), touched at its free end, pressed with
    ``preload`` 0.5 N (:data:`~ebantenna.simulate.contact.PRELOAD`, with its reason). The clamp
    is rigid.

    Parameters
    ----------
    diameter, free_length : float
        The rod's diameter and its length above the clamp, m.
    contact_height : float or None
        Height of the contact above the clamp, m, in ``(0, free_length]``; None: the free end.
    preload : float
        Contact force the contact spring is linearised at, N (> 0).
    rod_elements, probe_modes, rod_modes : int
        Beam elements of the rod, and fixed-interface modes kept of the probe and of the rod in
        the reduction. With the defaults (24 elements, 40 and 20 modes, the probe on the scene's
        40 elements) the coupled frequencies below 3 kHz agree with the unreduced system
        (:func:`~ebantenna.fem.coupling.monolithic_modes`) to 1.3e-5 relative over the five
        materials and the whole probe (0.04 Hz at 3 kHz, far below the 1 Hz resolution of a 1 s
        record); 64 and 40 modes reach 3e-7.

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> effect = ObjectModes()
    >>> round(effect.rod(material("steel")).cantilever_frequency(), 1)  # Hz
    137.3
    >>> round(effect.contact_stiffness(material("steel"), Probe()) / 1e5, 2)  # N/m
    1.85
    """

    name: ClassVar[str] = "object_modes"
    diameter: float = ROD_DIAMETER
    free_length: float = ROD_FREE_LENGTH
    contact_height: float | None = None
    preload: float = PRELOAD
    rod_elements: int = 24
    probe_modes: int = 40
    rod_modes: int = 20

    def __post_init__(self):
        check_positive("preload", self.preload)
        from ...fem.guards import MAX_ELEMENTS

        check_int("rod_elements", self.rod_elements, minimum=1, maximum=MAX_ELEMENTS)
        # no mesh the package solves has more than 2 (MAX_ELEMENTS + 1) degrees of freedom
        check_int("probe_modes", self.probe_modes, minimum=1, maximum=2 * (MAX_ELEMENTS + 1))
        check_int("rod_modes", self.rod_modes, minimum=1, maximum=2 * (MAX_ELEMENTS + 1))
        self.rod("steel")  # validates diameter, free_length and contact_height

    def rod(self, material: Material | str) -> Rod:
        """The touched rod of ``material``."""
        return Rod(material, self.diameter, self.free_length, self.contact_height)

    def contact_stiffness(self, obj: Material, probe: Probe, preload: float | None = None) -> float:
        """The contact spring: Hertz and tube wall in series, at ``preload`` (default the
        effect's), N/m."""
        check_bodies(obj, probe)
        force = self.preload if preload is None else check_positive("preload", preload)
        return tube_on_rod_stiffness(probe, obj, self.diameter, force).total

    def contact_loss_factor(
        self, obj: Material, probe: Probe, *, object_loss: bool, preload: float | None = None
    ) -> float:
        """Loss factor of the contact spring (dimensionless): the second value of
        :meth:`contact_spring`."""
        return self.contact_spring(obj, probe, object_loss=object_loss, preload=preload)[1]

    def contact_spring(
        self, obj: Material, probe: Probe, *, object_loss: bool, preload: float | None = None
    ) -> tuple[float, float]:
        """The contact spring at ``preload`` (default the effect's): its stiffness, N/m (as
        :meth:`contact_stiffness`), and its loss factor (dimensionless), by
        :func:`~ebantenna.simulate.contact.tube_on_rod_spring` (which says how the loss factor
        is shared between the bodies). With ``object_loss`` False the rod's share is lossless
        (:class:`ObjectDamping` not listed).

        Examples
        --------
        >>> from ebantenna import Probe
        >>> from ebantenna.probe import material
        >>> k, eta = ObjectModes().contact_spring(material("steel"), Probe(), object_loss=True)
        >>> k == ObjectModes().contact_stiffness(material("steel"), Probe())
        True
        """
        check_bodies(obj, probe)
        force = self.preload if preload is None else check_positive("preload", preload)
        return tube_on_rod_spring(probe, obj, self.diameter, force, object_loss=object_loss)


@dataclass(frozen=True)
class ObjectDamping(Effect):
    """The touched rod's own material damping.

    The rod's material loss factor ``eta`` (:data:`ebantenna.probe.MATERIALS`, with its sources)
    enters the coupled model as hysteretic damping ``K_rod (1 + i eta)``, and its share of the
    contact spring's compliance as well (:meth:`ObjectModes.contact_loss_factor`). Each coupled
    mode is damped by the bodies in proportion to the strain energy each holds in that mode
    (:mod:`ebantenna.fem.coupling`). This is the paper's explanation of material classification
    (the object absorbs the probe's energy according to its material); listing or leaving out
    this effect alone shows how much of the material information it carries. Requires
    :class:`ObjectModes`.
    """

    name: ClassVar[str] = "object_damping"


@dataclass(frozen=True)
class PreloadScatter(Effect):
    """The contact's preload varies from strike to strike.

    The servo stops where the search sweep met the object, and how far it drove on before it
    stopped sets how hard the probe presses; so the preload that :class:`~.objects.ObjectModes`
    linearises the contact at scatters. Each strike's preload is the effect's preload times a
    log-normal factor of standard deviation ``spread`` (in log units), and with it the Hertz
    stiffness (as ``preload^(1/3)``) and the coupled modes. Requires :class:`~.objects.ObjectModes`.
    Each strike then needs its own coupled eigenproblem (about 1.5 ms each).

    Parameters
    ----------
    spread : float
        Standard deviation of the log of the preload (dimensionless). Default 0.2: an assumption,
        as for the data set's sweep speed (the paper does not measure the rig's scatter).

    Examples
    --------
    >>> import numpy as np
    >>> f = PreloadScatter().factor(np.random.default_rng(0))
    >>> 0.3 < f < 3
    True
    """

    name: ClassVar[str] = "preload_scatter"
    stream: ClassVar[int] = 4
    spread: float = 0.2

    def __post_init__(self):
        check_nonnegative("spread", self.spread)

    def factor(self, rng: np.random.Generator) -> float:
        """One strike's preload relative to the nominal one (dimensionless, > 0)."""
        return float(np.exp(check_rng(rng).normal(0.0, self.spread)))


@dataclass(frozen=True)
class UnilateralContact(Effect):
    """A contact that only pushes: the probe lifts off the rod, rings free, and strikes again.

    Without this effect the contact spring of :class:`ObjectModes` pulls as readily as it
    pushes, and the strike is a sum of the coupled modes. With it, the X axis is the strike as
    the pan-tilt makes it, integrated in time between contact events
    (:mod:`ebantenna.simulate.strikes`, :func:`ebantenna.simulate.unilateral.unilateral_response`):
    the probe swings onto the rod at the sweep speed, the servo drives on by the overtravel that
    builds up the preload and stops, and whenever the contact force would turn into a pull the
    probe separates and flies free until the gap closes again (chatter). Both bodies keep their
    modes below the scene's ``max_frequency``; their loss factors become modal viscous damping.
    The Z axis is unchanged. Requires :class:`ObjectModes`.

    The ``paper`` scene lists it; it makes that scene about 4.8 times as costly to simulate (one
    run on one machine; the theory page on the touched object gives it). The study measures what
    a linear contact would change instead.

    Parameters
    ----------
    max_events : int
        Most contact changes per strike (>= 1); beyond them the contact is held closed, with a
        warning (undamped bodies, or a probe resting on the rod without preload, could chatter
        without end). The default leaves room for the longest chatter of the damped ``paper``
        scene: about 1,300 changes near the tip with its low-pass filter switched off.
    method : {"blocks", "steps"}
        How each strike is marched (``method`` of
        :func:`~ebantenna.simulate.unilateral.unilateral_response`): ``"blocks"``, the engine
        and the default, reads each contact state a block of steps ahead; ``"steps"``, the
        reference, takes every step in turn (:func:`.unilateral.march_step_by_step`), several
        times slower. Away from the tip, the same events, and signals within the rounding bound
        that the test suite derives (the ``paper`` scene at 0.17 m); in the long chatter
        near the tip the events depend on the last bits, and the two can part (brass at
        0.395 m: 290 against 318 contact changes; :mod:`ebantenna.simulate.unilateral`,
        "Reference and engine", gives the measurement).

    Examples
    --------
    >>> UnilateralContact().max_events
    4000
    >>> UnilateralContact(method="steps").method
    'steps'
    """

    name: ClassVar[str] = "unilateral_contact"
    max_events: int = 4000
    method: str = "blocks"

    def __post_init__(self):
        check_int("max_events", self.max_events, minimum=1)
        check_choice("method", self.method, tuple(MARCHES))


@dataclass(frozen=True)
class CoulombFriction(Effect):
    """Dry friction along the rod: the Z axis sticks to the rod and slips on it.

    Without this effect the probe slides along the rod freely, and Z rings at the free probe's
    frequencies (:mod:`ebantenna.simulate.modes`). With it, the contact point's motion along the
    rod meets Coulomb friction under the contact's preload ``N`` (static ``mu_s N``, kinetic
    ``mu_k N``): the tilt servo's stop sets it sliding, friction brakes it, and once it sticks Z
    rings as a probe pinned at the contact, until the force needed to hold it exceeds
    ``mu_s N``. Computed exactly between the stick and slip states
    (:mod:`ebantenna.simulate.stick_slip`, where its assumptions are named). Requires
    :class:`ObjectModes` (the preload). The ``paper`` scene leaves it out
    (``PAPER_LEAVES_OUT`` of :mod:`ebantenna.simulate.scene`).

    Parameters
    ----------
    static_friction, kinetic_friction : float
        ``mu_s >= mu_k >= 0`` (dimensionless). **Assumption:** one pair for every touched
        material, 0.45 for both by default: the middle of the range 0.4-0.5 that Autodesk
        Inventor's table "Friction factor for bolted connections" gives for Plexiglas (PMMA)
        on steel, the same in both of its columns (non-lubricated and lubricated). It is a
        factor for the faces of bolted joints, not a measurement of a tube sliding on a rod;
        no value was found for PMMA on aluminium, brass, oak or PVC, nor a kinetic value apart.
    max_events : int
        Most stick/slip changes per signal (>= 1); more raise
        :class:`~ebantenna.simulate.unilateral.ChatterError`.
    method : {"blocks", "steps"}
        How stick and slip are marched (``method`` of
        :func:`~ebantenna.simulate.stick_slip.stick_slip_response`): ``"blocks"``, the engine
        and the default, or ``"steps"``, the reference, every step in turn. The same
        stick/slip changes at each of nine contacts measured (the ``paper`` scene, 0.02 to
        0.395 m, brass, seed 1: their times within 1.2e-12 s of each other), and the signals
        within the rounding bound that the test suite derives (at 0.17 m).

    Examples
    --------
    >>> CoulombFriction().static_friction
    0.45
    """

    name: ClassVar[str] = "coulomb_friction"
    static_friction: float = 0.45
    kinetic_friction: float = 0.45
    max_events: int = 1000
    method: str = "blocks"

    def __post_init__(self):
        check_coefficients(self.static_friction, self.kinetic_friction)
        check_int("max_events", self.max_events, minimum=1)
        check_choice("method", self.method, tuple(MARCHES))
