"""``ebantenna bench``: the sweeps gathered into one report."""

import pytest

from ebantenna.bench import BENCHMARKS, run_benchmarks
from ebantenna.cli import main


def test_bench_writes_tables_and_plots(tmp_path):
    results = run_benchmarks(tmp_path, quick=True, only=["fem_accuracy"], show_progress=False)
    table = results["fem_accuracy"]["table"]
    assert "dense err" in table and "positions/s" in table
    md = (tmp_path / "bench.md").read_text()
    assert BENCHMARKS["fem_accuracy"] in md and "fem_accuracy.png" in md
    assert (tmp_path / "fem_accuracy.png").read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "bench.html").stat().st_size > 1000


def test_bench_rejects_an_unknown_sweep(tmp_path, capsys):
    with pytest.raises(ValueError, match="only must name benchmarks among"):
        run_benchmarks(tmp_path, only=["fem_accuracy", "gpu"])
    with pytest.raises(SystemExit):
        main(["bench", "--out", str(tmp_path), "--only", "nope"])
    assert "only must name benchmarks" in capsys.readouterr().err


def test_each_sweep_runs_once_and_feeds_table_and_figure(tmp_path, monkeypatch):
    from ebantenna.bench import fem_accuracy

    calls = []
    original = fem_accuracy.run

    def counted(quick=False):
        calls.append(quick)
        return original(quick)

    monkeypatch.setattr(fem_accuracy, "run", counted)
    drawn = []
    original_plot = fem_accuracy.plot
    monkeypatch.setattr(fem_accuracy, "plot",
                        lambda rows: drawn.append(rows) or original_plot(rows))
    results = run_benchmarks(tmp_path, quick=True, only=["fem_accuracy"], show_progress=False)
    assert calls == [True]
    # the figure is drawn from the very rows the table was written from
    assert len(drawn) == 1 and drawn[0] is results["fem_accuracy"]["rows"]
    assert str(results["fem_accuracy"]["rows"]["accuracy"][0]["N"]) in results["fem_accuracy"][
        "table"]
