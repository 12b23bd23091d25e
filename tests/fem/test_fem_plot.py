"""The probe's sketch is drawn from the objects it is given, so it always matches the code."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from ebantenna import Probe  # noqa: E402
from ebantenna.fem import Supports  # noqa: E402
from ebantenna.fem.plot import plot_probe  # noqa: E402


def _texts(ax):
    return {t.get_text(): t.get_position() for t in ax.texts}


@pytest.mark.parametrize(("length", "contact"), [(0.40, 0.30), (0.25, 0.05), (1.0, 0.999)])
def test_points_sit_at_the_hinge_the_contact_and_the_tip(length, contact):
    fig, ax = plt.subplots()
    plot_probe(Probe(length=length), Supports(contact=contact), ax=ax)
    texts = _texts(ax)
    # positions in cm: the same numbers times 100, to the last bit of one multiplication
    assert texts["P"][0] == 0.0
    assert texts["Q"][0] == pytest.approx(100 * contact, rel=1e-15)
    assert texts["R"][0] == pytest.approx(100 * length, rel=1e-15)
    # the two elements' dimensions add up to the length
    l1 = next(float(k.split("= ")[-1].split()[0]) for k in texts if k.startswith("$l_1"))
    l2 = next(float(k.split("= ")[-1].split()[0]) for k in texts if k.startswith("$l_2"))
    assert l1 + l2 == pytest.approx(100 * length, rel=1e-3)  # each printed to 4 digits
    assert ax.get_xlabel() == "distance from the hinge (cm)"
    plt.close(fig)


def test_no_contact_no_q_and_the_hinge_named():
    for hinge, name in (("clamped", "clamped"), ("pinned", "pinned"), (5.0, "elastic")):
        fig, ax = plt.subplots()
        plot_probe(Probe(), Supports(hinge=hinge), ax=ax)
        texts = _texts(ax)
        assert "Q" not in texts and {"P", "R"} <= set(texts)
        assert any(t.startswith(f"P: {name} hinge") for t in texts)
        plt.close(fig)


def test_tip_mass_drawn_only_when_there_is_one():
    fig, (a, b) = plt.subplots(2)
    plot_probe(Probe(), Supports(contact=0.2), ax=a)
    plot_probe(Probe(tip_mass=0.0025), Supports(contact=0.2), ax=b)
    assert a.get_legend() is None
    assert [t.get_text() for t in b.get_legend().get_texts()] == ["tip mass 2.5 g"]
    plt.close(fig)


def test_contact_beyond_the_tip_is_refused():
    with pytest.raises(ValueError, match="supports.contact must lie in"):
        plot_probe(Probe(length=0.4), Supports(contact=0.5))
    plt.close("all")
