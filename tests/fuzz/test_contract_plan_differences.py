"""The input contract of :func:`~ebantenna.device.plan.plan_differences`: what a refused resume
says is different between the folder's plan and the one given.

Each bad input is refused with a TypeError naming the parameter; each good one is checked
against the two plans' own settings, compared here key by key.
"""

from __future__ import annotations

import pytest

from ebantenna.device.plan import Plan, plan_differences
from ebantenna.simulate import builtin_scene
from ebantenna.study.recorded.planning import protocol_plan

A = Plan("demo", ("brass", "pvc"), (0.1, 0.2), 3).to_dict()


@pytest.mark.parametrize(("row", "stored", "given", "name"), [
    ("stored-list", [A], A, "stored"),
    ("stored-none", None, A, "stored"),
    ("given-plan-object", A, Plan("demo", ("brass",), (0.1,), 1), "given"),
    ("given-text", A, "demo", "given"),
])
def test_refuses_what_is_no_plan_as_a_dict(row, stored, given, name):
    with pytest.raises(TypeError, match=name):
        plan_differences(stored, given)


def test_equal_plans_differ_in_nothing():
    assert plan_differences(A, dict(A)) == []


def test_each_changed_setting_is_named_with_both_values_in_the_plans_order():
    b = Plan("demo", ("brass",), (0.1, 0.2), 2).to_dict()
    changed = [k for k in A if A[k] != b[k]]
    assert changed == ["materials", "repetitions"]  # the witness: the dicts compared by hand
    assert plan_differences(A, b) == [
        "the materials: ['brass', 'pvc'] in the folder, ['brass'] given",
        "the repetitions: 3 in the folder, 2 given",
    ]


def test_another_seed_of_a_built_in_plan_is_named_as_the_simulated_variation():
    # a resume of `record --simulated --quick` with another --seed: the touches are the same,
    # the simulated rows behind them are not
    scene = builtin_scene("paper")
    a = protocol_plan(quick=True, scene=scene, seed=0).to_dict()
    b = protocol_plan(quick=True, scene=scene, seed=3).to_dict()
    assert [k for k in a if a[k] != b[k]] == ["simulation"]
    (words,) = plan_differences(a, b)
    assert "simulated touches' variation" in words and "--seed" in words


def test_a_setting_in_one_plan_only_says_which():
    real = Plan("demo", ("brass",), (0.1,), 1).to_dict()
    simulated = {**real, "simulation": [{"seed": 1}]}
    assert plan_differences(real, simulated)[0].endswith("(given only)")
    assert plan_differences(simulated, real)[0].endswith("(in the folder only)")


def test_a_long_value_is_cut_in_the_message():
    many = {**A, "contacts_m": [round(0.005 * i, 3) for i in range(1, 80)]}
    (words,) = plan_differences(A, many)
    assert words.endswith("... given") and len(words) < 200


def contract_rows() -> dict[str, list[str]]:
    """The surface these rows cover (read by the inventory test)."""
    return {"ebantenna.device.plan.plan_differences": [
        "stored-list", "stored-none", "given-plan-object", "given-text", "equal",
        "changed-named", "seed-named", "one-side-only", "long-cut"]}
