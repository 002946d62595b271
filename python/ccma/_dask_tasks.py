"""Tasks on a Dask client whose results survive a lost worker (issue 28).

Dask runs a lost worker's unfinished tasks again by itself. A task that had
finished, though, keeps its result on the worker that ran it: if that worker
dies before the client gathers the result, the future is cancelled
(CancelledError). DaskTasks then submits the same task again (at most
`retries` times), so a batch survives a worker killed at any moment.
"""
from concurrent.futures import CancelledError


class DaskTasks:
    """submit(fn, *args) -> token; next_done() -> (token, result) as tasks finish."""

    def __init__(self, client, retries=3):
        from distributed import as_completed
        self._client = client
        self._retries = retries
        self._completed = as_completed()
        self._tasks = {}     # token -> (fn, args, priority, tries)
        self._token_of = {}  # future key -> token
        self._next = 0

    def submit(self, fn, *args, priority=0):
        token = self._next
        self._next += 1
        self._tasks[token] = (fn, args, priority, 0)
        self._start(token)
        return token

    def _start(self, token):
        fn, args, priority, _ = self._tasks[token]
        future = self._client.submit(fn, *args, pure=False, priority=priority)
        self._token_of[future.key] = token
        self._completed.add(future)

    def next_done(self):
        while True:
            future = next(self._completed)
            token = self._token_of.pop(future.key)
            try:
                result = future.result()
            except (CancelledError, OSError):  # its result was lost with its worker
                fn, args, priority, tries = self._tasks[token]
                if tries >= self._retries:
                    raise
                self._tasks[token] = (fn, args, priority, tries + 1)
                self._start(token)
                continue
            del self._tasks[token]
            return token, result
