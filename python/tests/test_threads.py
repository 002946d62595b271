"""Solves release the GIL: another Python thread keeps running meanwhile."""
import threading

import ccma
from conftest import ROOT


def test_replay_releases_the_gil():
    model = ccma.load_model(str(ROOT / "models" / "4dof_reduced.yaml"))
    waypoints = ccma.load_waypoints(str(ROOT / "models" / "paths" / "4dof_sequential.csv"))
    done = threading.Event()
    ticks = 0

    def work():
        ccma.replay(model, waypoints)  # one C++ call of about a second
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    while not done.is_set():
        ticks += 1  # runs only while the worker does not hold the GIL
    worker.join()
    # Holding the GIL for its whole C++ call, the worker would leave this
    # thread the ticks of a few milliseconds at most (~4e4 here); released,
    # about 3e6 in the ~0.5 s of the call.
    assert ticks > 1000000
