"""Tables of the study's uncertainty, from the stored summary of a full ``ebantenna reproduce`` run.

``.. study-intervals::`` renders the material classifiers on the three splits, each with its test
count, its Wilson 95 % interval and its spread over the split seeds; ``.. study-sensitivity::``
the touched rod's diameter and free length varied; ``.. study-ann-budget::`` the paper network
trained with two steps. Every number comes from ``docs/_data/reproduce_summary.json`` (see
:mod:`paper_map` for how to refresh it), none is typed into a page.
"""

from __future__ import annotations

from paper_map import SUMMARY_PATH, load_summary
from sphinx.util.docutils import SphinxDirective

__all__ = ["interval_lines", "repetition_lines", "sensitivity_lines", "ann_budget_lines",
           "setup"]

SPLITS = ("random", "grouped", "blocked")


def _cell(value, n, ci) -> str:
    """``83.2 % (n = 2000, 81.5-84.8)``."""
    return f"{100 * value:.1f} % (n = {n}, {100 * ci[0]:.1f}-{100 * ci[1]:.1f})"


def _spread(s: dict) -> str:
    return f"{100 * s['mean']:.1f} ± {100 * s['std']:.1f} %"


def _table(headers, rows) -> list[str]:
    """A ``list-table`` of strings."""
    out = [".. list-table::", "   :header-rows: 1", ""]
    for row in [headers, *rows]:
        out.append(f"   * - {row[0]}")
        out += [f"     - {c}" for c in row[1:]]
    return out + [""]


def interval_lines(summary: dict) -> list[str]:
    """The three classifiers on the three splits: seed 0 with count and interval, and the spread
    over the split seeds on the subset."""
    m = summary["materials"]
    named = {
        "paper's SVM": lambda k: (m[f"svm_{k}_test_accuracy"], m[f"svm_{k}_test_accuracy_n_test"],
                                  m[f"svm_{k}_test_accuracy_ci95"]),
        "position-aware": lambda k: _by_split(m, "position_aware_test_accuracy", k),
        "mode curves": lambda k: _by_split(m, "mode_curve_test_accuracy", k),
    }
    rows = []
    for name, get in named.items():
        for k in SPLITS:
            rows.append([name, k, _cell(*get(k)), _spread(m["seed_spread"][name][k])])
    subset = m["seed_spread"]["subset_recordings"]
    return _table(["classifier", "split", "seed 0 (n, 95 % interval)",
                   f"over split seeds ({subset} recordings)"], rows)


def _by_split(m: dict, name: str, k: str):
    return m[name][k], m[f"{name}_n_test"][k], m[f"{name}_ci95"][k]


def repetition_lines(summary: dict) -> list[str]:
    """The grouped SVM with the first repetitions of every position only, and the controls'
    baseline on its own reduced design."""
    m = summary["materials"]
    rows = [[r, _cell(v["accuracy"], v["accuracy_n_test"], v["accuracy_ci95"])]
            for r, v in sorted(m["svm_grouped_by_repetitions"].items(), key=lambda kv: int(kv[0]))]
    design = m["controls_design"]
    rows.append([f"controls' design ({design['recordings']} recordings), all effects on",
                 _cell(m["ablation"]["none"], m["ablation_n_test"]["none"],
                       m["ablation_ci95"]["none"])])
    return _table(["repetitions per position", "grouped SVM, seed 0 (n, 95 % interval)"], rows)


def sensitivity_lines(summary: dict) -> list[str]:
    """The rod's geometry varied: both classifiers and the closest materials' gap."""
    rows = [
        [f"{r['diameter_mm']:.0f}", f"{r['free_length_mm']:.0f}",
         _cell(r["svm_grouped_accuracy"], r["svm_grouped_accuracy_n_test"],
               r["svm_grouped_accuracy_ci95"]),
         _spread(r["svm_grouped_seed_spread"]),
         _cell(r["mode_curve_grouped_accuracy"], r["mode_curve_grouped_accuracy_n_test"],
               r["mode_curve_grouped_accuracy_ci95"]),
         " / ".join(r["closest_materials"]), f"{r['second_mode_gap_hz']:.2f}"]
        for r in summary["materials"]["rod_geometry"]
    ]
    return _table(["diameter (mm)", "free length (mm)", "grouped SVM (seed 0)",
                   "over split seeds", "mode curves (seed 0)", "closest materials",
                   "2nd-mode gap (Hz)"], rows)


def ann_budget_lines(summary: dict) -> list[str]:
    """The paper network trained by gradient descent with two steps."""
    runs = {k: v for k, v in summary["materials"]["ann_training_setup"].items()
            if isinstance(v, dict)}
    rows = [
        [name, f"{r['lr']:g}", f"{r['epochs']} ({r['max_epochs']})", r["stopped_by"],
         f"{r['final_loss']:.3f}",
         _cell(r["test_accuracy"], r["test_accuracy_n_test"], r["test_accuracy_ci95"])]
        for name, r in runs.items()
    ]
    return _table(["run", "step", "epochs (cap)", "stopped by", "final loss", "test"], rows)


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


class StudyRepetitions(_SummaryTable):
    build = staticmethod(repetition_lines)


class StudySensitivity(_SummaryTable):
    build = staticmethod(sensitivity_lines)


class StudyAnnBudget(_SummaryTable):
    build = staticmethod(ann_budget_lines)


def setup(app):
    app.add_directive("study-intervals", StudyIntervals)
    app.add_directive("study-repetitions", StudyRepetitions)
    app.add_directive("study-sensitivity", StudySensitivity)
    app.add_directive("study-ann-budget", StudyAnnBudget)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
