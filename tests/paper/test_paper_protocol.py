"""The paper's printed numbers say where they are printed, and the simulated data set, the default
probe and the paper scene follow them. (Which part may import which: tests/test_layers.py.)"""

import numpy as np
import pytest

from ebantenna.paper import printed
from ebantenna.paper.data import paper_dataset_plan
from ebantenna.paper.protocol import DATASET
from ebantenna.probe import material_names
from ebantenna.simulate import builtin_scene


def test_the_simulated_data_set_follows_the_paper_protocol():
    # simulate may not import the paper, so its data set builder carries the same design; this
    # is the witness that the two agree
    assert material_names() == DATASET.materials
    assert builtin_scene("paper").probe.length == pytest.approx(DATASET.probe_length)
    assert DATASET.probe_length == pytest.approx(printed.PROBE_LENGTH_CM.value / 100)
    plan = paper_dataset_plan(seed=0)
    contacts = np.unique(plan["contact"])
    np.testing.assert_allclose(np.diff(contacts), DATASET.contact_step, atol=1e-9)
    assert np.bincount(plan["repetition"]).size == DATASET.repetitions
    assert set(plan["material"]) == set(DATASET.materials)


def test_every_printed_number_says_where_it_is_printed():
    for name, number in printed.NUMBERS.items():
        assert number.where and number.quote, name
        assert number.unit in printed.UNITS, name
    with pytest.raises(ValueError, match="unit must be one of"):
        printed.PrintedNumber(1.0, "furlong", "nowhere", "")
    # the confusion matrices carry the printed accuracies (their counts are checked against
    # them in test_paper_experiments.py)
    assert printed.PAPER_SVM.reported_accuracy == {"train": 0.997, "test": 0.992}
    assert printed.PAPER_ANN.reported_accuracy == {"all": 0.808}
    with pytest.raises(ValueError, match="number must be a fraction"):
        printed.percent(printed.DEVIATION_CM)


def test_the_default_probe_and_paper_scene_are_what_the_paper_prints():
    from ebantenna.probe import Probe

    probe, scene = Probe(), builtin_scene("paper")
    assert probe.length == pytest.approx(printed.PROBE_LENGTH_CM.value / 100)
    assert probe.outer_diameter == pytest.approx(printed.TUBE_OUTER_DIAMETER_CM.value / 100)
    assert probe.inner_diameter == pytest.approx(printed.TUBE_INNER_DIAMETER_CM.value / 100)
    assert scene.fs == pytest.approx(1000 * printed.SAMPLING_FREQUENCY_KHZ.value)
