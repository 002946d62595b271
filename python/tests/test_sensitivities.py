"""ds/du and dX/du from the implicit function theorem against central
differences of re-solved forward problems (Python-side differences)."""
import numpy as np
import pytest

import ccma
from conftest import ROOT


def rotation_log(R):
    """The rotation vector of R (R small)."""
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2
    s = np.linalg.norm(w)
    c = (np.trace(R) - 1) / 2
    angle = np.arctan2(s, c)
    return w if s < 1e-15 else w * angle / s


def solved_at(model, state, u):
    forward = ccma.ForwardProblem(model)
    forward.set_state(state)
    # Not every single control can move alone (4dof_reduced: E ~ h^2 > 0
    # then); s_hat(u) = argmin E is still smooth, and ds/du is its derivative.
    r = forward.solve(u)
    assert r.converged and r.gradient_norm < 1e-12
    return forward


@pytest.mark.parametrize("name", ["4dof_reduced", "6dof_six_agents", "hybrid_ccma", "stewart_gough_6ups"])
def test_sensitivities_match_central_differences(name):
    model = ccma.load_model(str(ROOT / "models" / (name + ".yaml")))
    control = ccma.ControlProblem(model)
    p = model.end_effector.p_W_home
    assert control.move_to([p[0] + 0.02, p[1] - 0.01, p[2] + 0.015, 0.01, -0.01, 0.02]).converged
    state, u = control.forward.state, control.controls
    ds_du = control.state_sensitivity()
    dX_du = control.end_effector_jacobian()
    assert ds_du.shape == (model.state_size, len(control.effective_controls))
    assert dX_du.shape == (6, len(control.effective_controls))
    h = 1e-6
    for col, i in enumerate(control.effective_controls):
        up, um = u.copy(), u.copy()
        up[i] += h
        um[i] -= h
        fp, fm = solved_at(model, state, up), solved_at(model, state, um)
        # End-effector: position, then the rotation increment in world axes.
        dX = np.concatenate([(fp.end_effector.position - fm.end_effector.position) / (2 * h),
                             rotation_log(fp.end_effector.rotation @ fm.end_effector.rotation.T) / (2 * h)])
        scale = max(1.0, np.abs(dX).max())
        assert np.abs(dX_du[:, col] - dX).max() < 1e-6 * scale, (name, i)
        # Every body: [dphi (world), dp] per body, as the state tangent.
        ds = np.concatenate([np.concatenate([rotation_log(a.rotation @ b.rotation.T), a.position - b.position])
                             for a, b in zip(fp.body_poses(), fm.body_poses())]) / (2 * h)
        assert np.abs(ds_du[:, col] - ds).max() < 1e-6 * max(1.0, np.abs(ds).max()), (name, i)


def test_objective_gradient_matches_differences():
    model = ccma.load_model(str(ROOT / "models" / "4dof_reduced.yaml"))
    control = ccma.ControlProblem(model)
    target = [0.01, 0.02, 0.61, 0, 0, 0.01]
    O, g = control.objective(target)
    u = control.controls
    h = 1e-6
    for col, i in enumerate(control.effective_controls):
        values = []
        for sign in (1, -1):
            v = u.copy()
            v[i] += sign * h
            other = ccma.ControlProblem(model)
            other.set_controls(v)
            values.append(other.objective(target)[0])
        assert abs(g[col] - (values[0] - values[1]) / (2 * h)) < 1e-6 * max(1.0, abs(g[col]))
    assert O > 0
