"""Tables of the study's uncertainty, from the stored summary of a full ``ebantenna reproduce`` run.

``.. study-intervals::`` renders the material classifiers on the three splits, each over all its
folds with its unit of replication, its 95 % interval on that unit, the folds' spread and the
design effect; ``.. study-repetitions::`` the grouped SVM against the repetitions per position;
``.. study-controls::`` every control paired against its reference, with the verdict and the
difference the design detects; ``.. study-sensitivity::`` the touched rod's diameter and free
length varied; ``.. study-ann-budget::`` the paper network trained with two steps and the long
run. Every number comes from ``docs/_data/reproduce_summary.json`` (see :mod:`paper_map` for how
to refresh it) and is printed by the formatters the report uses
(:func:`ebantenna.paper.uncertainty.percent`, :func:`~ebantenna.paper.uncertainty.span`,
:func:`~ebantenna.paper.uncertainty.points`): none is typed into a page, none rounded twice.
"""

from __future__ import annotations

from paper_map import SUMMARY_PATH, load_summary
from sphinx.util.docutils import SphinxDirective

from ebantenna.paper.uncertainty import detectable_cell, detectable_text, percent, points, span

__all__ = ["value_text", "study_role", "interval_lines", "design_effect_lines",
           "repetition_lines", "controls_lines", "sensitivity_lines",
           "ann_budget_lines", "cell", "setup"]

SPLITS = ("random", "grouped", "blocked")


def cell(entries: dict, name: str, key: str | None = None) -> str:
    """``83.2 % (n = 2000 in 16 positions, 76.0-90.5)`` from the summary's keys of accuracy
    ``name`` (one value of a by-key dict when ``key`` is given)."""
    def get(suffix):
        v = entries[f"{name}{suffix}"]
        return v if key is None else v[key]

    unit, units = get("_unit"), get("_n_units")
    plural = unit + ("s" if units != 1 and not unit.endswith("s") else "")
    return (f"{percent(get(''))} (n = {get('_n_test')} in {units} {plural}, "
            f"{span(get('_ci95'))})")


def _folds(entries: dict, name: str, key: str | None = None) -> str:
    """The folds' standard deviation, or '-' for a single split."""
    v = entries.get(f"{name}_fold_std")
    if v is not None and key is not None:
        v = v.get(key)
    return "-" if v is None else percent(v)


def _deff(entries: dict, name: str, key: str | None = None) -> str:
    v = entries.get(f"{name}_design_effect")
    if v is not None and key is not None:
        v = v.get(key)
    return "-" if v is None else f"{v:.1f}"


def _table(headers, rows) -> list[str]:
    """A ``list-table`` of strings."""
    out = [".. list-table::", "   :header-rows: 1", ""]
    for row in [headers, *rows]:
        out.append(f"   * - {row[0]}")
        out += [f"     - {c}" for c in row[1:]]
    return out + [""]


def interval_lines(summary: dict) -> list[str]:
    """The three classifiers on the three splits of the main data set (random: the paper's one
    split; grouped and blocked: all folds), with unit, interval, the folds' spread and the
    design effect; the recording-level Wilson interval beside them for contrast."""
    m = summary["materials"]
    named = {
        "paper's SVM": lambda k: (m, f"svm_{k}_test_accuracy", None),
        "position-aware": lambda k: (m, "position_aware_test_accuracy", k),
        "mode curves": lambda k: (m, "mode_curve_test_accuracy", k),
    }
    rows = []
    for name, get in named.items():
        for k in SPLITS:
            entries, key, sub = get(k)
            rec = entries[f"{key}_recording_ci95"]
            rows.append([name, k, cell(entries, key, sub), _folds(entries, key, sub),
                         _deff(entries, key, sub), span(rec if sub is None else rec[sub])])
    return _table(["classifier", "split", "accuracy (n in units, 95 % interval on the unit)",
                   "folds' std", "design effect",
                   "recording-level Wilson (too narrow)"], rows)


def design_effect_lines(summary: dict) -> list[str]:
    """One paragraph, generated from the summary: the main grouped SVM's recordings, units,
    design effect and the two intervals."""
    m = summary["materials"]
    name = "svm_grouped_test_accuracy"
    n, g, deff = m[f"{name}_n_test"], m[f"{name}_n_units"], m[f"{name}_design_effect"]
    return [
        f"The paper's SVM on whole held-out positions of the main data set, over all folds: "
        f"{percent(m[name])} of {n} test recordings, which come from {g} positions "
        f"({n // g} recordings each). Their design effect is {deff:.1f}: the {n} recordings "
        f"carry about as much as {n / deff:.0f} independent ones. Counting every recording, "
        f"Wilson's interval would be {span(m[f'{name}_recording_ci95'])} %; on the position "
        f"it is {span(m[f'{name}_ci95'])} %.",
        "",
    ]


def repetition_lines(summary: dict) -> list[str]:
    """The grouped SVM (all folds) with the first repetitions of every position only, and the
    controls' baseline on its own reduced design."""
    m = summary["materials"]
    rows = [[r, cell(v, "accuracy"), _deff(v, "accuracy")]
            for r, v in sorted(m["svm_grouped_by_repetitions"].items(), key=lambda kv: int(kv[0]))]
    design = m["controls_design"]
    rows.append([f"controls' design ({design['recordings']} recordings), all effects on",
                 cell(m, "ablation", "none"), _deff(m, "ablation", "none")])
    table = _table(["repetitions per position", "grouped SVM, all folds", "design effect"], rows)
    return table + ["", *_paired_repetitions(m["svm_grouped_repetitions_paired"])]


def _paired_repetitions(p: dict) -> list[str]:
    """The most repetitions against the fewest, paired on the recordings both test, written as
    every paired comparison the pages show (``_pair_text``)."""
    head = (f"Paired on the {p['n_test']} recordings both rows test (the first "
            f"{'repetition' if p['fewest'] == 1 else str(p['fewest']) + ' repetitions'} of each "
            f"material at each of the {p['n_units']} positions), {p['most']} repetitions against "
            f"{p['fewest']}: ")
    return [head + _pair_text(p) + "."]


def controls_lines(summary: dict) -> list[str]:
    """Every control paired against its reference on the same rows and folds."""
    paired = summary["materials"]["controls_paired"]
    rows = []
    for name, p in paired.items():
        label = name.replace("ablation:", "switched off: ")
        if p.get("identical"):
            rows.append([label, _alike(p), "nothing to resolve", "-"])
            continue
        lo, hi = (points(v).split()[0] for v in p["ci95"])
        rows.append([label, f"{points(p['difference'])} ({lo} to {hi})",
                     "yes" if p["resolved"] else "no",
                     _detectable(p)])
    return _table(["comparison", "paired difference (95 % interval on the position)",
                   "resolved", "detectable at 80 % power, points: spread / whole positions"],
                  rows)


def _detectable(pair: dict) -> str:
    """The two detectable differences of a paired comparison of the summary, in points (the
    table's header says so)."""
    return detectable_cell(pair["detectable_difference_80"],
                           pair["detectable_difference_80_clustered"])


def _alike(pair: dict) -> str:
    """A paired comparison whose two conditions count as many right in every cluster (its
    ``identical``): said so, with no interval, verdict or detectable difference."""
    units = pair["n_units"]
    return (f"none: as many test recordings right under both in each of the {units} "
            f"{pair['unit']}{'s' if units != 1 else ''}")


def sensitivity_lines(summary: dict) -> list[str]:
    """The rod's geometry varied: both classifiers over all folds and the closest materials'
    gap."""
    rows = []
    for r in summary["materials"]["rod_geometry"]:
        against = r.get("svm_against_scene_rod")
        rows.append([
            f"{r['diameter_mm']:.0f}", f"{r['free_length_mm']:.0f}",
            cell(r, "svm_grouped_accuracy"),
            "(the scene's rod)" if against is None else _alike(against)
            if against.get("identical") else points(against["difference"])
            + (" (resolved)" if against["resolved"] else " (not resolved)"),
            cell(r, "mode_curve_grouped_accuracy"),
            " / ".join(r["closest_materials"]), f"{r['second_mode_gap_hz']:.2f}"])
    return _table(["diameter (mm)", "free length (mm)", "grouped SVM, all folds",
                   "against the scene's rod", "mode curves, all folds", "closest materials",
                   "2nd-mode gap (Hz)"], rows)


def ann_budget_lines(summary: dict) -> list[str]:
    """The paper network trained by gradient descent with two steps, and the long run."""
    setup = summary["materials"]["ann_training_setup"]
    runs = {k: v for k, v in setup.items() if isinstance(v, dict) and "max_epochs" in v
            and k != "long_run"}
    rows = [
        [name, f"{r['lr']:g}", f"{r['epochs']} ({r['max_epochs']})", r["stopped_by"],
         f"{r['final_loss']:.3f}", cell(r, "test_accuracy")]
        for name, r in runs.items()
    ]
    long = setup.get("long_run")
    if long is not None:
        rows.append(["no validation stop", f"{long['lr']:g}",
                     f"{long['epochs'][-1]} ({long['max_epochs']})", long["stopped_by"], "-",
                     _long_test(long)])
    return _table(["run", "step", "epochs (cap)", "stopped by", "final loss", "test"], rows)


def _long_test(long: dict) -> str:
    """The long run's test cell: where it stopped at the first checkpoint whose test accuracy
    reached the paper's, that epoch and the accuracy there, picked on the test rows and so
    given no test interval; otherwise its last checkpoint's accuracy with its interval."""
    reached = long.get("reached_paper_test_epoch")
    if reached is None or reached != long["epochs"][-1]:
        return cell(long, "test_accuracy")
    return (f"first reaches the paper's {percent(long['paper_value'])} at epoch {reached} "
            f"({percent(long['test_accuracy'])} there, picked on the test rows: no test "
            "interval)")


def _lookup(summary: dict, dotted: str):
    """``a.b.c`` of the summary; a part that is no key of a dict is tried as a whole name
    (keys such as ``ablation:gravity`` or ``object_damping+unilateral_contact`` hold dots
    nowhere, but may hold colons and pluses)."""
    node = summary
    for part in dotted.split("."):
        node = node[part]
    return node


def value_text(summary: dict, text: str) -> str:
    """``KEY|SPEC`` of the summary as the report prints it: ``pct`` a percentage
    (:func:`~ebantenna.paper.uncertainty.percent`), ``span`` an interval's ends, ``acc`` an
    accuracy's cell (``KEY`` the accuracy's name: its ``_n_test``, ``_unit``, ``_n_units`` and
    ``_ci95`` beside it), ``pair`` a paired comparison with its verdict (``KEY`` an entry of
    ``controls_paired`` or the like), ``sqrtFORMAT`` the square root in ``FORMAT``,
    ``minFORMAT`` and ``maxFORMAT`` the least and the largest of a list in ``FORMAT``, anything
    else a format specification."""
    key, _, spec = text.partition("|")
    if spec == "acc":
        parent, _, name = key.rpartition(".")
        return cell(_lookup(summary, parent) if parent else summary, name)
    value = _lookup(summary, key)
    if spec == "pct":
        return percent(value)
    if spec == "span":
        return span(value)
    if spec.startswith("sqrt"):  # the square root, in the format that follows
        return format(value ** 0.5, spec[4:])
    if spec.startswith(("min", "max")):  # a list's least or largest, in the format that follows
        return format((min if spec.startswith("min") else max)(value), spec[3:])
    if spec == "pair":
        return _pair_text(value)
    return format(value, spec)


def _pair_text(value: dict) -> str:
    """A paired comparison of the summary with its interval and verdict (``value_text``'s
    ``pair``)."""
    if value.get("identical"):
        return f"({_alike(value).removeprefix('none: ')}: no difference to resolve)"
    lo, hi = (points(v).split()[0] for v in value["ci95"])
    verdict = (f"resolved, {value['direction']}" if value["resolved"] else
               "not resolved; detectable at 80 % power: "
               + detectable_text(value["detectable_difference_80"],
                                 value["detectable_difference_80_clustered"], value["unit"]))
    return f"{points(value['difference'])} (95 % CI {lo} to {hi}; {verdict})"


def study_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``:study:`KEY|SPEC``` inline: a number of the stored summary (:func:`value_text`)."""
    from docutils import nodes

    try:
        shown = value_text(load_summary()["summary"], text)
    except (KeyError, TypeError) as missing:
        msg = inliner.reporter.warning(f"the stored summary has no {text!r}: {missing}",
                                       line=lineno)
        return [inliner.problematic(rawtext, rawtext, msg)], [msg]
    return [nodes.Text(shown)], []


class _SummaryTable(SphinxDirective):
    """A table from the stored summary, built by ``self.build``."""

    has_content = False
    build = None

    def run(self):
        self.env.note_dependency(str(SUMMARY_PATH))
        record = load_summary()
        try:
            lines = type(self).build(record["summary"])
        except KeyError as missing:  # a summary stored before the study wrote this key
            lines = [
                f"*The stored summary (commit {record['made']['commit']}) holds no "
                f"{missing.args[0]!r} yet: refresh* ``docs/_data/reproduce_summary.json`` *from "
                "a full run (``python docs/_ext/paper_map.py SUMMARY.json``) to fill this table.*"
            ]
        return self.parse_text_to_nodes("\n".join(lines))


class StudyIntervals(_SummaryTable):
    build = staticmethod(interval_lines)


class StudyDesignEffect(_SummaryTable):
    build = staticmethod(design_effect_lines)


class StudyRepetitions(_SummaryTable):
    build = staticmethod(repetition_lines)


class StudyControls(_SummaryTable):
    build = staticmethod(controls_lines)


class StudySensitivity(_SummaryTable):
    build = staticmethod(sensitivity_lines)


class StudyAnnBudget(_SummaryTable):
    build = staticmethod(ann_budget_lines)


def setup(app):
    app.add_role("study", study_role)
    app.add_directive("study-intervals", StudyIntervals)
    app.add_directive("study-design-effect", StudyDesignEffect)
    app.add_directive("study-repetitions", StudyRepetitions)
    app.add_directive("study-controls", StudyControls)
    app.add_directive("study-sensitivity", StudySensitivity)
    app.add_directive("study-ann-budget", StudyAnnBudget)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
