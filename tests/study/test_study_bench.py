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
    mlp = [p for p in parts if p["part"].startswith("MLP")]
    assert mlp[-1]["part"].endswith("the three parts above together")
    assert mlp[-1]["seconds"] == sum(p["seconds"] for p in mlp[:-1])
    assert mlp[-1]["share"] == sum(p["share"] for p in mlp[:-1])


def test_ml_speed_mlp_parts_alternate_with_the_fit_they_are_shares_of():
    from ebantenna.bench import ml_speed

    X, y = ml_speed.spectra_like(150, 8, 3, seed=1)
    calls = []
    fit = lambda: calls.append("theirs")  # noqa: E731
    parts = ml_speed.where_time_goes(X, y, 2.0, 4.0, epochs=1, batch_size=64, adam_fit=fit,
                                     repeat=3)
    assert calls == ["theirs"] * 9  # three repetitions for each of the three parts
    for p in (p for p in parts if p["part"].startswith("MLP")):
        assert p["share"] > 0 and p["share"] != p["seconds"] / 4.0  # not over adam_seconds


def test_small_set_parts_clock_the_compiled_fits_and_restore_what_they_clock():
    from ebantenna.bench import ml_speed
    from ebantenna.ml import smo as smo_module
    from ebantenna.ml.kernels import Kernel

    rows = [{"task": task, "data": "iris 112x4", "engine": engine, "sklearn_seconds": 2.0}
            for task in ml_speed.SMALL_CASES for engine in ("numpy", "compiled")]
    gram, loop = Kernel.gram, smo_module.SMO_ENGINES["compiled"]
    parts = ml_speed.small_set_parts(rows, repeat=1)
    assert Kernel.gram is gram and smo_module.SMO_ENGINES["compiled"] is loop
    if "compiled" not in ml_speed.engines():
        assert parts == []  # nothing to clock without numba
        return
    # one part per compiled row, each share over that row's scikit-learn time
    assert [p["part"] for p in parts] == [
        f"{task}, iris: kernel entries + compiled loop" for task in ml_speed.SMALL_CASES]
    for p in parts:
        kernel, loop_share = (float(w.split()[1]) for w in
                              p["note"].split(", ")[:2])
        assert p["seconds"] > 0 and p["share"] == p["seconds"] / 2.0
        assert abs(kernel + loop_share - p["share"]) <= 0.011  # two shares rounded to 0.01


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


def test_compare_takes_the_ratios_within_each_repetition():
    from ebantenna.bench import ml_speed

    # a clock that makes the calls last, in order: ours 2, theirs 1; ours 3, theirs 6; ours 8,
    # theirs 2 (s): within-repetition ratios 2, 0.5 and 4; best times 2 and 1
    ticks = iter([0, 2, 2, 3, 3, 6, 6, 12, 12, 20, 20, 22])
    row = ml_speed.compare("t", lambda: None, lambda: None, lambda m: 0.0, repeat=3,
                           data="d", engine="e", clock=lambda: next(ticks))
    assert (row["ratio_min"], row["ratio_median"]) == (0.5, 2.0)
    assert (row["ours_seconds"], row["sklearn_seconds"], row["ratio"]) == (2, 1, 2.0)
    assert (row["data"], row["engine"]) == ("d", "e")


def test_small_set_rows_time_each_engine_on_each_set(monkeypatch):
    from ebantenna.bench import ml_speed

    seen = []

    def fake_compare(task, ours, theirs, score, repeat, *, data, engine):
        model = ours()  # the batch of our fits, on the engine chosen by on_engine
        seen.append((task, data.split()[0], engine, ml_speed.os.environ["EBANTENNA_ENGINE"]))
        return {"ours_seconds": 1.0, "sklearn_seconds": 1.0, "ours_accuracy": score(model)}

    monkeypatch.setattr(ml_speed, "compare", fake_compare)
    monkeypatch.setattr(ml_speed, "SMALL_SETS", ("iris",))
    before = ml_speed.os.environ.get("EBANTENNA_ENGINE")
    rows = ml_speed.small_set_rows(repeat=1, batch_seconds=0.0)
    engines = ml_speed.engines()
    assert [(task, engine) for task, _, engine, _ in seen] == [
        (task, engine) for task in ("SVC rbf fit", "SVC rbf fit, libsvm_compat=True",
                                    "SVC linear fit, C=100") for engine in engines]
    assert all(name == "iris" and env == engine for _, name, engine, env in seen)
    assert all(r["ours_accuracy"] > 0.9 for r in rows)  # iris held out: the fits are real
    assert ml_speed.os.environ.get("EBANTENNA_ENGINE") == before  # restored after


def test_every_sweep_runs_alone_from_the_benchmarks_folder_and_is_named_in_the_help(capsys):
    # the README and the CLI guide: "each runs alone from benchmarks/"
    import benchmark_scripts

    for name in BENCHMARKS:
        script = benchmark_scripts.FOLDER / f"{name}.py"
        assert script.is_file(), f"{name} has no script in benchmarks/"
        assert f"from ebantenna.bench.{name} import main" in script.read_text(encoding="utf-8")
        assert f"{name}.py`" in (benchmark_scripts.FOLDER.parent / "README.md").read_text(
            encoding="utf-8")
    with pytest.raises(SystemExit):
        main(["bench", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert all(name in help_text for name in BENCHMARKS)
