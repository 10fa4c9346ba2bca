"""paperlib.parallel.run_many: same results in-process, in processes and on Dask."""

import numpy as np
import pytest

from paperlib.parallel import progress_enabled, run_many, spawn_seeds


def draw(task, rng):
    return task, rng.integers(0, 2**62, size=3).tolist()


def square(task):
    return task * task


def fail_on_three(task):
    if task == 3:
        raise ValueError("three")
    return task


def test_results_in_task_order_and_independent_of_workers():
    serial = run_many(draw, range(6), rng=42, workers=1)
    pooled = run_many(draw, range(6), rng=42, workers=2)
    assert serial == pooled
    assert [task for task, _ in serial] == list(range(6))
    assert len({tuple(numbers) for _, numbers in serial}) == 6  # every run has its own stream


def test_same_seed_same_output_other_seed_differs():
    assert run_many(draw, range(3), rng=1, workers=1) == run_many(draw, range(3), rng=1, workers=1)
    assert run_many(draw, range(3), rng=1, workers=1) != run_many(draw, range(3), rng=2, workers=1)


def test_generator_parent_spawns_fresh_children_each_time():
    rng = np.random.default_rng(5)
    first, second = run_many(draw, range(2), rng=rng, workers=1), run_many(draw, range(2), rng=rng, workers=1)
    assert first != second
    again = np.random.default_rng(5)
    assert run_many(draw, range(2), rng=again, workers=1) == first


def test_unseeded_runs():
    assert run_many(square, [1, 2, 3], seeded=False, workers=2) == [1, 4, 9]
    assert run_many(square, [], seeded=False) == []


def test_errors_propagate():
    with pytest.raises(ValueError, match="three"):
        run_many(fail_on_three, range(5), seeded=False, workers=2)
    with pytest.raises(ValueError, match="three"):
        run_many(fail_on_three, range(5), seeded=False, workers=1)


@pytest.mark.parametrize("bad", [0, -1, 1.5, True])
def test_bad_workers(bad):
    with pytest.raises(ValueError, match="workers"):
        run_many(square, [1], seeded=False, workers=bad)


@pytest.mark.parametrize("bad", ["seed", 1.5, True])
def test_bad_rng(bad):
    # a value of the wrong kind is a TypeError from the shared check (paperlib._checks.check_rng)
    with pytest.raises(TypeError, match="rng"):
        spawn_seeds(bad, 2)


def nested_runner():
    def run(task, rng):
        return task

    return run


def test_unpicklable_function_names_the_fix():
    """A lambda or nested function cannot go to worker processes: a TypeError says what to write instead."""
    for fn in (lambda task, rng: task, nested_runner()):
        with pytest.raises(TypeError, match=r"cannot be pickled .*top level of a module.*workers=1") as caught:
            run_many(fn, range(4), rng=0, workers=2)
        assert f"fn={fn.__qualname__!r}" in str(caught.value)  # names the culprit
    assert run_many(lambda task, rng: task, range(3), rng=0, workers=1) == [0, 1, 2]  # in this process: fine


def test_unpicklable_task_names_the_fix():
    import threading

    with pytest.raises(TypeError, match=r"first task \(a lock\).*plain data"):
        run_many(square, [threading.Lock(), threading.Lock()], seeded=False, workers=2)


def test_progress_bar_is_optional_and_changes_nothing(capsys):
    quiet = run_many(draw, range(4), rng=7, workers=1)
    assert "%|" not in capsys.readouterr().err
    shown = run_many(draw, range(4), rng=7, workers=1, progress=True, desc="draws")
    err = capsys.readouterr().err
    assert "draws" in err and "4/4" in err
    assert shown == quiet
    run_many(draw, range(4), rng=7, workers=1, progress=None)  # auto: stderr is captured, not a terminal
    assert "%|" not in capsys.readouterr().err
    assert progress_enabled(None) is False and progress_enabled(True) is True
    with pytest.raises(TypeError, match="progress must be True, False or None"):
        run_many(draw, range(2), rng=7, workers=1, progress="on")


def test_ci_installs_the_dask_extra():
    """The Dask tests below run in CI only if `make test` (what .ci/run calls) installs the [dask] extra."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    install = [line for line in (root / "Makefile").read_text().splitlines() if "pip install" in line and "-e" in line]
    assert install and all("dask" in line for line in install), install
    assert "make test" in (root / ".ci" / "run").read_text()


@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed (pip install -e .[dask])")
    # two small worker processes: tasks and results really go through pickling, as on a remote cluster
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  memory_limit="1GiB") as cluster:
        with distributed.Client(cluster) as client:
            yield client


@pytest.mark.dask
def test_dask_local_cluster_gives_the_same_results(dask_client):
    on_dask = run_many(draw, range(6), rng=42, client=dask_client)
    assert on_dask == run_many(draw, range(6), rng=42, workers=1)
    assert on_dask == run_many(draw, range(6), rng=42, workers=2)


@pytest.mark.dask
def test_dask_envelopes_are_bit_identical_to_local_runs(dask_client):
    """What docs/scale_out.md promises: an envelope computed on a cluster equals the local one bit for bit."""
    from paperlib.pointprocess import Lest, MultiStraussHard, Window, envelope, rmh

    window = Window.rectangle((0, 1), (0, 1))
    model = MultiStraussHard([120.0], gamma=0.4, r=[[0.05]], hc=[[0.02]])
    observed = rmh(model, window, 20_000, rng=1)
    for options in (dict(model=model, simulate_kwargs=dict(T=5_000)), dict()):  # a Gibbs null model, then CSR
        local = envelope(observed, Lest, nsim=12, rng=5, workers=1, **options)
        remote = envelope(observed, Lest, nsim=12, rng=5, client=dask_client, **options)
        assert list(local.columns) == list(remote.columns)
        for column in local.columns:
            assert local[column].to_numpy().tobytes() == remote[column].to_numpy().tobytes(), column
        other = envelope(observed, Lest, nsim=12, rng=6, workers=1, **options)
        assert other["lo"].to_numpy().tobytes() != local["lo"].to_numpy().tobytes()  # the check can fail
