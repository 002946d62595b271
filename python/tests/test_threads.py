"""Threads: solves release the GIL (another Python thread keeps running meanwhile), and one
problem used by two threads at once raises RuntimeError instead of corrupting its state."""
import threading
import time

import numpy as np

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
    # about 3e6 in the ~0.5 s of the call on an idle machine, and 9e5 seen
    # with ctest -j2 running other tests on the other core.
    assert ticks > 250000


MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
# 0.1 m sideways, 0.05 m up in steps of 20 um: ~5600 path steps, about 0.3 s,
# so two threads started together overlap.
SLOW = dict(max_step_m=2e-5)


def far_target(model):
    p = model.end_effector.p_W_home
    return [p[0] + 0.1, p[1], p[2] + 0.05, 0, 0, 0]


def run_together(*calls):
    """Runs the calls on threads released together; returns (result or exception) per call."""
    barrier = threading.Barrier(len(calls))
    out = [None] * len(calls)

    def run(i):
        barrier.wait()
        try:
            out[i] = calls[i]()
        except Exception as e:  # noqa: BLE001 -- the test inspects it
            out[i] = e

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(calls))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def test_one_control_problem_on_two_threads_raises_and_stays_usable():
    model = ccma.load_model(MODEL)
    alone = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW))
    expected = alone.move_to(far_target(model))
    assert expected.converged
    shared = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW))
    out = run_together(lambda: shared.move_to(far_target(model)), lambda: shared.move_to(far_target(model)))
    errors = [r for r in out if isinstance(r, Exception)]
    results = [r for r in out if not isinstance(r, Exception)]
    assert len(errors) == 1 and len(results) == 1, out
    assert isinstance(errors[0], RuntimeError)
    assert str(errors[0]) == "ccma.ControlProblem is being used by another thread; use one problem per thread"
    # The winner's solve was not disturbed: the same steps and controls as alone.
    assert results[0].converged and results[0].steps == expected.steps
    np.testing.assert_array_equal(results[0].controls, expected.controls)
    np.testing.assert_array_equal(shared.controls, expected.controls)
    # And the problem works afterwards: back home as the lone problem goes.
    home = [*model.end_effector.p_W_home, 0, 0, 0]
    back = shared.move_to(home)
    assert back.converged and back.error < 1e-9
    np.testing.assert_array_equal(back.controls, alone.move_to(home).controls)


def test_the_inner_forward_problem_is_guarded_with_its_control_problem():
    model = ccma.load_model(MODEL)
    control = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW))
    forward = control.forward
    u = forward.controls

    def solve_a_little_later():
        time.sleep(0.1)  # the move takes ~0.3 s: it is well inside by now
        return forward.solve(u)

    out = run_together(lambda: control.move_to(far_target(model)), solve_a_little_later)
    assert out[0].converged, out
    assert isinstance(out[1], RuntimeError), out
    assert str(out[1]) == "ccma.ForwardProblem is being used by another thread; use one problem per thread"
    # Free again once the move is over.
    assert forward.solve(forward.controls).assembled


def test_two_problems_on_two_threads_both_work():
    model = ccma.load_model(MODEL)
    target = far_target(model)
    expected = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW)).move_to(target)
    a = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW))
    b = ccma.ControlProblem(model, ccma.ControlOptions(**SLOW))
    out = run_together(lambda: a.move_to(target), lambda: b.move_to(target))
    for r in out:
        assert not isinstance(r, Exception), r
        assert r.converged and r.steps == expected.steps
        np.testing.assert_array_equal(r.controls, expected.controls)
