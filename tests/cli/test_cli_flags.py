"""Every flag of ``record``, ``acquire``, ``bench`` and the data options of ``dataset`` and
``reproduce`` refuses a bad value with exit code 2 and one line naming it, before any work:
nothing is written, nothing is printed on stdout.

Counts and shares are bounded by the flag's own type: ``record --attempts`` from 1 to 100 (the
I2C layer's bound on retries: 10**6 attempts were accepted), ``--max-lost`` and
``--inject-faults`` in [0, 1) (their errors named the Python parameter, ``error_rate``, not the
flag). The simulated bus's clock ``--bus-hz`` is bounded by the fastest I2C mode (3.4 MHz) and
``--transfer-timeout`` by ten times Linux's default adapter timeout (0, NaN and 1e300 were accepted
and ended the run as "servos could not be released").
"""

from __future__ import annotations

import json
import os

import pytest

from ebantenna.cli import main

#: The plan every ``record`` row reads (one touch): written in the row's folder.
PLAN = {"name": "fz", "materials": ["brass"], "contacts_m": [0.1], "repetitions": 1,
        "probe_length": 0.4, "search": {}}
RECORD = ["record", "--simulated", "--plan", "plan.json", "--out", "rec"]
ACQUIRE = ["acquire", "--simulated", "--out", "acq"]
HARDWARE = ["acquire", "--bus", "1", "--out", "acq"]

#: ``surface -> [(argv, words the one line must hold)]``
ROWS = {
    "cli:record": [(["record", "--simulated", "--plan", "none.json", "--out", "rec"],
                    ["none.json"]),
                   (["record", "--simulated", "--out", "rec", "--plan", "plan.json",
                     "--quick"], ["--quick"])],
    "cli:record --attempts": [(RECORD + ["--attempts", v], ["--attempts"])
                              for v in ("0", "101", "10**9", "2.5", "-1")],
    "cli:record --bus": [(["record", "--bus", v, "--plan", "plan.json", "--out", "rec"],
                          ["--bus"]) for v in ("x", "-1", "1.5")]
    + [(RECORD + ["--bus", "1"], ["--bus"])],
    "cli:record --inject-faults": [(RECORD + ["--inject-faults", v], ["--inject-faults"])
                                   for v in ("2", "1", "-0.1", "nan", "inf", "x")],
    "cli:record --max-lost": [(RECORD + ["--max-lost", v], ["--max-lost"])
                              for v in ("1", "1.5", "-1", "nan", "x")],
    "cli:record --json": [(RECORD + ["--json", "--attempts", "0"], ["--attempts"])],
    "cli:record --no-wait": [(RECORD + ["--no-wait"], ["--no-wait", "--bus"])],
    "cli:record --oe-gpio": [(RECORD + ["--oe-gpio", "5"], ["--oe-gpio"]),
                             (RECORD + ["--oe-gpio", "-1"], ["--oe-gpio"])],
    "cli:record --quick": [(["record", "--simulated", "--quick", "--plan", "plan.json",
                             "--out", "rec"], ["--quick"])],
    "cli:record --scene": [(RECORD + ["--scene", "nope"], ["scene", "nope"])],
    "cli:record --seed": [(RECORD + ["--seed", v], ["--seed"]) for v in ("-1", "2**70", "x")],
    "cli:record --simulated": [(["record", "--simulated", "--bus", "1", "--plan", "plan.json",
                                 "--out", "rec"], ["--simulated"])],
    "cli:acquire --chip-reset-at": [(ACQUIRE + ["--chip-reset-at", "-1"], ["chip_reset_at"]),
                                    (ACQUIRE + ["--chip-reset-at", "nan"], ["chip_reset_at"]),
                                    (HARDWARE + ["--chip-reset-at", "0.1"],
                                     ["--chip-reset-at", "--simulated"])],
    "cli:acquire --clock-drift": [(ACQUIRE + ["--clock-drift", v], ["clock_drift"])
                                  for v in ("nan", "1e300", "-0.95")],
    "cli:acquire --free-running-divider": [(HARDWARE + ["--free-running-divider"],
                                            ["--free-running-divider", "--simulated"])],
    "cli:acquire --measured-pwm-hz": [(ACQUIRE + ["--measured-pwm-hz", v], ["measured_pwm_hz"])
                                      for v in ("-5", "0", "nan")],
    "cli:acquire --oe-gpio": [(ACQUIRE + ["--oe-gpio", v], ["--oe-gpio"])
                              for v in ("-1", "x")],
    "cli:acquire --oscillator-hz": [(ACQUIRE + ["--oscillator-hz", v], ["oscillator_hz"])
                                    for v in ("0", "-1", "nan")],
    "cli:acquire --release-fails": [(HARDWARE + ["--release-fails"],
                                     ["--release-fails", "--simulated"])],
    "cli:acquire --repeat-last-byte": [(HARDWARE + ["--repeat-last-byte"],
                                        ["--repeat-last-byte", "--simulated"])],
    "cli:acquire --stuck-bus": [(ACQUIRE + ["--stuck-bus", "x", "y"], ["--stuck-bus"]),
                                (ACQUIRE + ["--stuck-bus", "-1", "5"], ["stuck_at"]),
                                (ACQUIRE + ["--stuck-bus", "5", "nan"], ["stuck_duration"]),
                                (ACQUIRE + ["--stuck-bus", "5"], ["--stuck-bus"])],
    "cli:acquire --slow-host": [(ACQUIRE + ["--slow-host", a, b], [f"slow_host {which}"])
                                for a, b, which in (("1", "0.1", "share"), ("nan", "0.1", "share"),
                                                    ("-0.1", "0.1", "share"),
                                                    ("0.1", "nan", "longest"),
                                                    ("0.1", "11", "longest"),
                                                    ("0.1", "-1", "longest"))]
    + [(ACQUIRE + ["--slow-host", "0.1"], ["--slow-host"]),
       (HARDWARE + ["--slow-host", "0.1", "0.1"], ["--slow-host", "--simulated"])],
    "cli:acquire --bus-hz": [(ACQUIRE + ["--bus-hz", v], ["bus_hz"])
                             for v in ("0", "-1", "nan", "inf", "1e300", "3.5e6")]
    + [(ACQUIRE + ["--bus-hz", "x"], ["--bus-hz"]),
       (HARDWARE + ["--bus-hz", "400000"], ["--bus-hz", "--simulated"])],
    "cli:acquire --transfer-timeout": [(ACQUIRE + ["--transfer-timeout", v], ["transfer_timeout"])
                                       for v in ("-1", "nan", "1e300", "11")]
    + [(HARDWARE + ["--transfer-timeout", "1"], ["--transfer-timeout", "--simulated"])],
    "cli:bench": [(["bench", "--only", "x"], ["only", "x"])],
    "cli:bench --only": [(["bench", "--only", "nope"], ["only", "nope"]),
                         (["bench", "--only"], ["--only"])],
    "cli:bench --out": [(["bench", "--out", ""], ["--out"]),
                        (["bench", "--out", "plan.json"], ["--out"])],
    "cli:bench --quick": [(["bench", "--quick", "--only", "x"], ["only"])],
    "cli:bench --json": [(["bench", "--json", "--only", "x"], ["only"])],
    "cli:dataset --quick": [(["dataset", "--quick", "--out", ""], ["--out"]),
                            (["dataset", "--quick", "--seed", "-1", "--out", "d"], ["--seed"])],
    "cli:reproduce --cache": [(["reproduce", "--quick", "--cache", ""], ["--cache"]),
                              (["reproduce", "--quick", "--cache", "plan.json"], ["--cache"])],
    "cli:reproduce --quick": [(["reproduce", "--quick", "--data", "plan.json"], ["--quick"])],
}

CASES = [(surface, argv, words) for surface, rows in ROWS.items() for argv, words in rows]


@pytest.mark.parametrize(("surface", "argv", "words"), CASES,
                         ids=[" ".join(argv) for _, argv, _ in CASES])
def test_a_bad_flag_is_refused_in_one_line_before_any_work(tmp_path, monkeypatch, capsys,
                                                           surface, argv, words):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "plan.json").write_text(json.dumps(PLAN), encoding="utf-8")
    with pytest.raises(SystemExit) as end:
        main(argv)
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert end.value.code == 2 and lines and lines[-1].startswith("ebantenna"), err
    assert "Traceback" not in err and out == "", (out, err)
    for word in words:
        assert word in lines[-1], (word, lines[-1])
    assert sorted(os.listdir(tmp_path)) == ["plan.json"]  # nothing written


def contract_rows() -> dict[str, list[str]]:
    """The commands and flags these rows cover (read by the inventory test)."""
    return {surface: [" ".join(argv) for argv, _ in rows] for surface, rows in ROWS.items()}
