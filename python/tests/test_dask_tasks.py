"""DaskTasks survives losing the scattered shared value and a task's result (python/ccma/_dask_tasks.py)."""
import time

import pytest

from ccma._dask_tasks import DaskTasks


def _join(shared, part, seconds=0.0):
    time.sleep(seconds)
    return shared + ":" + part


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        yield c


def test_tasks_return_their_results_with_the_shared_value(client):
    tasks = DaskTasks(client, "model")
    tokens = {tasks.submit(_join, str(i)): i for i in range(5)}
    got = dict(tasks.next_done() for _ in tokens)
    assert got == {t: f"model:{i}" for t, i in tokens.items()}


def test_a_shared_value_lost_before_submitting_is_scattered_again(client):
    tasks = DaskTasks(client, "model")
    lost = tasks._shared
    client.cancel(lost)  # as if every worker holding the scattered text had died
    token = tasks.submit(_join, "a")
    assert tasks.next_done() == (token, "model:a")
    assert tasks._shared.key != lost.key


def test_a_shared_value_lost_while_its_tasks_run_is_scattered_again(client):
    tasks = DaskTasks(client, "model")
    lost = tasks._shared
    tokens = {tasks.submit(_join, str(i), 0.3): i for i in range(3)}
    client.cancel(lost)  # cancels the running tasks that depend on it too
    got = dict(tasks.next_done() for _ in tokens)
    assert got == {t: f"model:{i}" for t, i in tokens.items()}
    assert tasks._shared.key != lost.key


def test_a_task_cancelled_every_time_gives_up_after_its_retries(client):
    from concurrent.futures import CancelledError
    tasks = DaskTasks(client, "model", retries=2)
    starts = []
    original = tasks._start

    def start_and_cancel(token):
        original(token)
        starts.append(token)
        client.cancel([f for f in tasks._completed.futures if tasks._token_of.get(f.key) == token])

    tasks._start = start_and_cancel
    tasks.submit(_join, "a")
    with pytest.raises(CancelledError):
        tasks.next_done()
    assert len(starts) == 3  # the first try and two retries
