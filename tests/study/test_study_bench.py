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


def test_ml_speed_parts_count_the_solver_updates_and_restore_what_they_clock():
    from ebantenna.bench import ml_speed
    from ebantenna.ml import SVC
    from ebantenna.ml import svc as svc_module
    from ebantenna.ml.kernels import Kernel

    gram, solve = Kernel.gram, svc_module.solve_smo
    X, y = ml_speed.spectra_like(150, 8, 3, seed=1)
    parts = ml_speed.where_time_goes(X, y, 2.0, 4.0, epochs=1, batch_size=64)
    assert Kernel.gram is gram and svc_module.solve_smo is solve
    rows = {p["part"]: p for p in parts}
    # SMO is deterministic: the clocked fit takes the updates of an unclocked one
    assert rows["SVC default: SMO loop"]["updates"] == SVC().fit(X, y).n_iter_.sum()
    assert rows["SVC libsvm_compat: SMO loop"]["updates"] == (
        SVC(libsvm_compat=True).fit(X, y).n_iter_.sum())
    # the parts of a fit are disjoint stretches of it, and each share is over the given time
    for p in parts:
        assert p["seconds"] >= 0
        assert p["share"] == p["seconds"] / (2.0 if p["part"].startswith("SVC") else 4.0)
    products = rows["MLP adam, 1 BLAS thread: gathers and the two 64x8x53 products"]
    assert "3 mini-batches" in products["note"]


def test_clocked_restores_the_attribute_when_the_call_raises():
    from types import SimpleNamespace

    from ebantenna.bench._timing import clocked

    def fails():
        raise RuntimeError("boom")

    owner, totals = SimpleNamespace(f=fails), {}
    with pytest.raises(RuntimeError, match="boom"), clocked(owner, "f", totals):
        owner.f()
    assert owner.f is fails and "f" not in totals


def test_compare_alternates_the_sides_and_keeps_the_best_time_of_each():
    from ebantenna.bench import ml_speed

    calls = []
    row = ml_speed.compare("t", lambda: calls.append("ours") or 1.0,
                           lambda: calls.append("theirs") or 0.5, lambda m: 2 * m, repeat=3)
    assert calls == ["ours", "theirs"] * 3  # alternated, so load on the machine hits both
    assert row["task"] == "t" and row["ours_accuracy"] == 2.0 and row["sklearn_accuracy"] == 1.0
    assert row["ours_seconds"] > 0 and row["sklearn_seconds"] > 0
    assert row["ratio"] == row["ours_seconds"] / row["sklearn_seconds"]  # the same division
    with pytest.raises(ValueError, match="repeat must be >= 1"):
        ml_speed.run(repeat=0)
