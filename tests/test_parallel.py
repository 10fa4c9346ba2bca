"""paperlib.parallel.run_many: same results in-process, in processes and on Dask."""

import numpy as np
import pytest

from paperlib.parallel import run_many, spawn_seeds


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


@pytest.mark.dask
def test_dask_local_cluster_gives_the_same_results():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            on_dask = run_many(draw, range(6), rng=42, client=client)
    assert on_dask == run_many(draw, range(6), rng=42, workers=1)
