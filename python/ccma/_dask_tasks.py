"""Tasks on a Dask client whose results survive a lost worker (issue 28).

Every task takes one shared value first (the model file's text), scattered
to every worker once. Dask runs a lost worker's unfinished tasks again by
itself. Two losses it does not repair:
- a task that had finished keeps its result on the worker that ran it: if
  that worker dies before the client gathers it, the future is cancelled;
- scattered data has no recipe: if the scheduler counts every copy as lost,
  each task that needs it is cancelled, and so is any resubmission that
  names the same scattered key.
On a cancelled future DaskTasks scatters the shared value again when its
copy is gone, waits a moment (a restarting worker settles), and submits the
same task again, at most `retries` times per task, so a batch survives a
worker killed at any moment.
"""
import time
from concurrent.futures import CancelledError


class DaskTasks:
    """submit(fn, *args) runs fn(shared, *args); next_done() -> (token, result) as tasks finish."""

    def __init__(self, client, shared, retries=5):
        from distributed import as_completed
        self._client = client
        self._shared_value = shared
        self._shared = self._scatter()
        self._retries = retries
        self._completed = as_completed()
        self._tasks = {}     # token -> (fn, args, priority, tries)
        self._token_of = {}  # future key -> token
        self._next = 0

    def _scatter(self):
        # hash=False: a fresh key per call. A key hashed from the value would
        # be shared with an earlier call on this client, and releasing that
        # call's future would cancel this call's tasks.
        return self._client.scatter(self._shared_value, broadcast=True, hash=False)

    def submit(self, fn, *args, priority=0):
        token = self._next
        self._next += 1
        self._tasks[token] = (fn, args, priority, 0)
        self._start(token)
        return token

    def _start(self, token):
        fn, args, priority, _ = self._tasks[token]
        if self._shared.status != "finished":
            self._shared = self._scatter()
        future = self._client.submit(fn, self._shared, *args, pure=False, priority=priority)
        self._token_of[future.key] = token
        self._completed.add(future)

    def next_done(self):
        while True:
            future = next(self._completed)
            token = self._token_of.pop(future.key)
            try:
                result = future.result()
            except (CancelledError, OSError):  # its result, or the shared value, was lost with a worker
                fn, args, priority, tries = self._tasks[token]
                if tries >= self._retries:
                    raise
                time.sleep(min(0.1 * 2 ** tries, 2.0))
                self._tasks[token] = (fn, args, priority, tries + 1)
                self._start(token)
                continue
            del self._tasks[token]
            return token, result
