"""Batches of simulation runs: in this process, through a process pool and through a
dask.distributed cluster of two worker processes (the test extra installs dask, so
this runs in CI): identical numbers in the same order."""

import pytest

import kinetostatics as ks
from balance.machine import BalancingMachine, CoastDown
from kinetostatics.simulation import (
    SERIAL,
    SimulationDiverged,
    SimulationError,
    crosscheck_many,
    run_batch,
    study,
)
from tests.kinetostatics.simulation.test_simulation import constant_speed, scene_path

STUDY = dict(steps=(500, 1000, 2000), iterations=(10,), samples_per_revolution=45)
MANY = ["four_bar", "slider_crank", "scotch_yoke"]
MANY_SETTINGS = dict(steps_per_revolution=1000, iterations=30, samples_per_revolution=45)


def _same_study(a, b):
    cols = ["case", "dt", "steps_per_revolution", "iterations", "max_error", "diverged",
            "drift", "order"]
    assert a.table[cols].equals(b.table[cols])          # identical numbers, same order
    assert a.order == b.order and a.order_points == b.order_points


@pytest.mark.slow
def test_study_and_many_through_a_process_pool_match_serial():
    from concurrent.futures import ProcessPoolExecutor
    serial = study(ks.example("four_bar"), **STUDY, executor=SERIAL)
    scenes = [constant_speed(n) for n in MANY]
    many = crosscheck_many(scenes, **MANY_SETTINGS, executor=SERIAL)
    assert [m["title"] for m in many] == [ks.load_scene(scene_path(n)).title for n in MANY]
    # measured at 1000 steps: 1.25e-4, 5.36e-5 and 7.77e-6
    assert all(m["max_error"] < t for m, t in zip(many, (3e-4, 1.2e-4, 2e-5), strict=True))
    with ProcessPoolExecutor(max_workers=2) as pool:
        _same_study(serial, study(ks.example("four_bar"), **STUDY, executor=pool))
        again = crosscheck_many(scenes, **MANY_SETTINGS, executor=pool)
    assert [m["errors"] for m in again] == [m["errors"] for m in many]
    # the default: processes (one per core)
    _same_study(serial, study(ks.example("four_bar"), **STUDY))
    # every run timed itself in its worker
    assert (serial.table.ms_per_revolution > 0).all()


def test_run_batch_executors():
    assert run_batch(abs, [-3, 2, -1], executor=SERIAL) == [3, 2, 1]
    assert run_batch(abs, [-5]) == [5]                  # one item: no pool
    assert run_batch(abs, []) == []
    for bad in ("threads", object(), 4):
        with pytest.raises(SimulationError):
            run_batch(abs, [1, 2], executor=bad)
    with pytest.raises(SimulationError):
        crosscheck_many([ks.example("four_bar")], step=100, executor=SERIAL)


def test_a_diverged_run_crosses_a_process_boundary():
    """A worker's SimulationDiverged comes back whole (it pickles with its fields)."""
    from concurrent.futures import ProcessPoolExecutor
    with ProcessPoolExecutor(max_workers=1) as pool, \
            pytest.raises(SimulationDiverged, match="the simulation diverged at") as exc:
        crosscheck_many([ks.example("shaper")], steps_per_revolution=1000, iterations=10,
                        samples_per_revolution=45, executor=pool)
    # measured: drift 8.7e-5 m at 333 deg (1.5e-4 of the size; 30 times the bound)
    assert exc.value.iterations == 10 and exc.value.drift > 1e-4 * exc.value.size


@pytest.mark.slow
def test_batches_through_a_dask_cluster():
    """A LocalCluster of two worker processes runs a study (with a diverged setting)
    and a balancing machine's runs unchanged: the same numbers as in this process."""
    # (imported here, in the full suite's test only: at the module's top every process
    # collecting the quick tier imported dask's cluster, 0.4 s of CPU each)
    import distributed
    grid = dict(steps=(500, 1000), iterations=(10,), samples_per_revolution=45)
    bm = BalancingMachine(coast_down=CoastDown(duration=1.0))
    sets = [[(0.02, 0.1, a)] for a in (0.0, 90.0, 200.0)]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        ex = client.get_executor()
        four = study(ks.example("four_bar"), **grid, executor=ex)
        shaper = study(ks.example("shaper"), **grid, executor=ex)
        recs = bm.runs(sets, executor=ex)
    _same_study(study(ks.example("four_bar"), **grid, executor=SERIAL), four)
    _same_study(study(ks.example("shaper"), **grid, executor=SERIAL), shaper)
    assert shaper.table.diverged.all()
    serial = bm.runs(sets, executor=SERIAL)
    assert [r.amplitude for r in recs] == [r.amplitude for r in serial]
    assert [r.x.tolist() for r in recs] == [r.x.tolist() for r in serial]
