"""The bench from Python: the command line's run, its tables as records, progress, Ctrl-C."""

import csv
import json
import threading
import time
import _thread

import pytest

import swarmplan
from conftest import without_times

SMALL = dict(sharing=["none", "pb"], route=["sequential", "astar"], exact_limit=1, threads=2)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_row(record, row):
    """A record (Python data) equals a CSV row (text) field by field."""
    for k, v in record.items():
        text = row[k]
        if v is None:
            assert text == "", k
        elif isinstance(v, bool):
            assert text == str(v).lower(), k
        elif isinstance(v, float):
            assert float(text) == pytest.approx(v, rel=1e-12, abs=1e-12), k
        else:
            assert text == str(v), k


def test_bench_is_the_command_lines_bench(cli, tmp_path):
    calls = []
    got = swarmplan.bench(limit=4, out=tmp_path / "py", progress=lambda d, t: calls.append((d, t)), **SMALL)
    cli("bench", "--limit", 4, "--sharing", "none,pb", "--route", "sequential,astar",
        "--exact-limit", 1, "--threads", 2, "--out", tmp_path / "cli")
    for table in ["requests", "hops", "stops"]:
        rows = read_csv(tmp_path / "cli" / f"{table}.csv")
        assert len(got.tables[table]) == len(rows) > 0
        for record, row in zip(got.tables[table], rows):
            same_row({k: v for k, v in record.items() if k != "ms"}, row)
    # combinations: none (once), pb under both positionings, for each route; plus the optimal
    # routes the gaps need.
    assert len(got.tables["requests"]) == 4 * len(got.config["combos"])
    assert got.config["limit"] == 4 and got.config["exact_limit"] == 1
    assert without_times(got.summary["methods"]) is not None
    assert calls and calls[-1][0] == calls[-1][1] > 0
    assert all(b[0] >= a[0] for a, b in zip(calls, calls[1:]))
    assert "requests" in repr(got)


def test_bench_is_reproducible_and_frames(tmp_path):
    a = swarmplan.bench(limit=3, **SMALL)
    b = swarmplan.bench(limit=3, out=tmp_path / "b", **dict(SMALL, threads=1))
    assert without_times(a.tables["requests"]) == without_times(b.tables["requests"])
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pandas"):
            a.frame("requests")
    else:
        frame = a.frame("requests")
        assert len(frame) == len(a.tables["requests"])
        assert list(frame.columns) == list(a.tables["requests"][0].keys())
    with pytest.raises(KeyError):
        a.frame("nothing")


def test_bench_refuses_bad_options(tmp_path):
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.bench(limit=2, sharing=["pbx"])
    assert (e.value.code, e.value.field) == ("E0026", "sharing")
    assert "idle-support" in e.value.action and "fair" in e.value.action
    with pytest.raises(TypeError):
        swarmplan.bench(limit=2, colour="red")
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.bench(limit=2, distance_bucket_km=0)
    assert e.value.code == "E7006"
    swarmplan.bench(limit=1, out=tmp_path, exact_limit=0, sharing=["none"], route=["astar"])
    with pytest.raises(swarmplan.SwarmplanError) as e:
        swarmplan.bench(limit=1, out=tmp_path, exact_limit=0, sharing=["none"], route=["astar"])
    assert e.value.code == "E7005"


def test_the_defaults_are_the_command_lines(cli, tmp_path):
    # Only the request count and the exact subset are set (to keep it short): every other
    # setting is its default on both fronts, and the configurations they record are equal.
    py = swarmplan.bench(limit=1, out=tmp_path / "py", exact_limit=0, threads=2)
    cli("bench", "--request-limit", 1, "--exact-limit", 0, "--threads", 2, "--out", tmp_path / "cli")
    want = json.loads((tmp_path / "cli" / "config.json").read_text())
    assert py.config == want
    assert json.loads((tmp_path / "py" / "config.json").read_text()) == want
    # The core alone draws no figures; the command line does.
    assert py.summary["figures"] == []
    assert not (tmp_path / "py" / "figures").exists()
    assert (tmp_path / "cli" / "figures").is_dir()
    assert py.summary["command"][0] == "swarmplan.bench"
    assert py.to_dict()["config"] == want


def test_a_long_run_releases_the_gil_and_stops_on_ctrl_c():
    # Event-driven, so a busy machine cannot reorder it: the interrupt is sent only once the
    # bench has reported progress (it is running on its worker) and another Python thread has
    # ticked 20 times since then (the GIL is free while it plans). On a quiet machine the
    # KeyboardInterrupt follows the interrupt within one 50 ms poll; the test allows 10 s.
    ticks = []
    started = threading.Event()
    stop = threading.Event()
    sent = []

    def progress(done, total):
        if done > 0:
            started.set()

    def count():
        while not stop.is_set():
            if started.is_set():
                ticks.append(1)
            time.sleep(0.01)

    def interrupt():
        # 10,000 requests take about 3 min on one quiet core without the joint optimum: the first
        # plan comes well before.
        if not started.wait(timeout=600):
            return
        while len(ticks) < 20 and not stop.is_set():
            time.sleep(0.01)
        if not stop.is_set():
            sent.append(time.monotonic())
            _thread.interrupt_main()

    counter = threading.Thread(target=count)
    interrupter = threading.Thread(target=interrupt)
    counter.start()
    interrupter.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            swarmplan.bench(
                limit=10_000,
                sharing=["pb"],
                route=["sequential"],
                exact_limit=0,
                joint=False,
                threads=1,
                progress=progress,
            )
        raised = time.monotonic()
    finally:
        stop.set()
        started.set()
        counter.join()
        interrupter.join()
    assert sent, "the interrupt was never sent: the bench reported no progress"
    assert len(ticks) >= 20  # the other thread ran while the bench planned
    assert raised - sent[0] < 10.0
