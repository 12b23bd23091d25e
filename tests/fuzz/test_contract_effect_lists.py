"""The input contract of a scene's effect list (:func:`ebantenna.simulate.scene.make_effects`):
a string, a number or a repeated or unknown effect is refused by name; a good list comes back
made and in the simulator's order."""

from __future__ import annotations

import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna.simulate import effects as fx  # noqa: E402
from ebantenna.simulate import scene  # noqa: E402

S = "ebantenna.simulate.scene.make_effects"


def all_rows():
    return [
        Row(S, "str", lambda: scene.make_effects("gravity"), ("effects must",)),
        Row(S, "int", lambda: scene.make_effects(3), ("effects must",)),
        Row(S, "repeated", lambda: scene.make_effects(["gravity", "gravity"]), ("gravity",)),
        Row(S, "unknown", lambda: scene.make_effects(["rain"]), ("rain",)),
        Row(S, "params-with-instance", lambda: scene.make_effects([fx.Gravity(), 2.0]),
            ("effect must", "effect")),
        Row(S, "dict-bad-params", lambda: scene.make_effects({"gravity": {"g": -1.0}}), ("g",)),
        Row(S, "ordered", lambda: scene.make_effects({"kalman": {}, "gravity": {"g": 9.0}}),
            same=lambda r: [e.name for e in r] == ["gravity", "kalman"] and r[0].g == 9.0),
    ]


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, "ebantenna.simulate.scene.")
