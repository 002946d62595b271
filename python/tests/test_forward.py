"""Forward solves checked without the C++ code: the constraints recomputed
in NumPy from the body poses, and closed forms."""
import numpy as np
import pytest

import ccma
from conftest import MODELS, csv_numbers, run_tool
from test_agreement import control_target, shifted_controls


def world_point(poses, body, p):
    if body < 0:  # the ground
        return np.asarray(p)
    return poses[body].rotation @ p + poses[body].position


def world_axis(poses, body, a):
    return np.asarray(a) if body < 0 else poses[body].rotation @ a


def test_constraints_hold_in_numpy(model_path):
    """Every joint closes (points coincide, axes agree) and every base sits
    on the ground at its controls, recomputed here from body poses alone.
    The controls come from a control move, so they are reachable."""
    model = ccma.load_model(model_path)
    moved = ccma.ControlProblem(model).move_to(control_target(model))
    assert moved.converged
    u = moved.controls
    forward = ccma.ForwardProblem(model)
    r = forward.assemble(u)
    assert r.assembled and r.residual_energy < 1e-20
    poses = forward.body_poses()
    for j in model.joints:
        pa = world_point(poses, j.body_a, j.p_A)
        pb = world_point(poses, j.body_b, j.p_B)
        if j.type == "prismatic":
            axis = world_axis(poses, j.body_a, j.a_A)
            d = pb - pa
            assert np.linalg.norm(d - axis * (axis @ d)) < 1e-10, j.name
        else:
            assert np.linalg.norm(pa - pb) < 1e-10, j.name
        if j.type == "revolute":
            assert np.linalg.norm(np.cross(world_axis(poses, j.body_a, j.a_A),
                                           world_axis(poses, j.body_b, j.a_B))) < 1e-10, j.name
        if j.type == "universal":
            assert abs(world_axis(poses, j.body_a, j.a_A) @ world_axis(poses, j.body_b, j.b_B)) < 1e-10, j.name
    for k, base in enumerate(model.mobile_bases):
        p = poses[base.body]
        i = model.base_control(k)
        np.testing.assert_allclose(p.position[:2], u[i:i + 2], atol=1e-10)
        if base.type == "legged":  # body at (x, y, height) turned by Rz(theta) Ry(pitch) Rx(roll)
            theta, height, roll, pitch = u[i + 2], u[i + 3], u[i + 4], u[i + 5]
            assert abs(p.position[2] - height) < 1e-10
            heading = [np.cos(theta) * np.cos(pitch), np.sin(theta) * np.cos(pitch), -np.sin(pitch)]
            np.testing.assert_allclose(p.rotation[:, 0], heading, atol=1e-10)
            continue
        assert abs(p.position[2]) < 1e-12
        np.testing.assert_allclose(p.rotation[:, 2], [0, 0, 1], atol=1e-10)  # turns about z only
        if base.actuation == "complete":
            assert abs(np.arctan2(p.rotation[1, 0], p.rotation[0, 0]) - u[i + 2]) < 1e-10


# Models whose controls are all base poses (no actuated joints).
BASE_DRIVEN = [m for m in MODELS if ccma.load_model(str(m)).num_controls == 3 * ccma.load_model(str(m)).num_bases]


@pytest.mark.parametrize("path", BASE_DRIVEN, ids=lambda m: m.stem)
def test_translating_every_base_translates_the_end_effector(path):
    """Closed form: moving every base by the same (dx, dy) translates the
    whole mechanism, so X_EE = home + (dx, dy, 0), rotation unchanged."""
    model = ccma.load_model(str(path))
    u = model.home_controls.copy()
    for k in range(model.num_bases):
        u[3 * k:3 * k + 2] += [0.03, -0.02]
    r = ccma.ForwardProblem(model).assemble(u)
    np.testing.assert_allclose(r.end_effector.position, model.end_effector.p_W_home + [0.03, -0.02, 0], atol=1e-10)
    np.testing.assert_allclose(r.end_effector.rotation, np.eye(3), atol=1e-10)


def test_a_rigid_move_is_checked_and_its_gradient_bound_flagged():
    """4dof_reduced hangs from its bases alone: moving them all by one
    planar rigid motion moves the mechanism without an iteration, checked on
    the residuals; gradient_norm is then a bound (flagged). Without the
    predictor the solve iterates and reports the gradient itself. (That the
    bound holds at the same state: tests/planar_rigid_motion_test.cc.)"""
    model = ccma.load_model(str([m for m in MODELS if m.stem == "4dof_reduced"][0]))
    forward = ccma.ForwardProblem(model)
    u = model.home_controls.copy()
    assert forward.assemble(u).assembled
    for k in range(model.num_bases):
        u[3 * k:3 * k + 2] += [0.004, -0.003]
    r = forward.solve(u)
    assert r.iterations == 0 and r.converged and r.assembled
    assert r.gradient_norm_is_bound
    assert 0 < r.gradient_norm < 1e-11
    plain = ccma.ForwardProblem(model, ccma.ForwardOptions(rigid_motion_predictor=False))
    exact = plain.assemble(u)
    assert exact.iterations > 0 and exact.assembled
    assert not exact.gradient_norm_is_bound


def test_base_driven_models_are_found():
    assert len(BASE_DRIVEN) >= 6  # the paper's five and 4dof_differential


def test_state_round_trip_and_reset():
    model = ccma.load_model(str(MODELS[0]))
    forward = ccma.ForwardProblem(model)
    home = forward.state
    assert home.shape == (model.num_bodies, 7)
    forward.assemble(shifted_controls(model))
    moved = forward.state
    assert np.abs(moved - home).max() > 1e-3
    forward.set_state(home)
    np.testing.assert_array_equal(forward.state, home)
    forward.reset_to_home()
    np.testing.assert_array_equal(forward.controls, model.home_controls)


def test_state_rows_are_scalar_first_quaternions_then_positions(model_path):
    """Rows [qw, qx, qy, qz, px, py, pz], the quaternion order of BodyPose.quaternion
    and of the tool's JSON; home bodies of identity rotation read [1, 0, 0, 0]."""
    model = ccma.load_model(model_path)
    forward = ccma.ForwardProblem(model)
    home = forward.state
    for b, body in enumerate(model.bodies):
        if np.array_equal(body.R_WB_home, np.eye(3)):
            np.testing.assert_array_equal(home[b, :4], [1, 0, 0, 0])
    forward.assemble(shifted_controls(model))
    state = forward.state
    cli = run_tool("simulate", "--model=" + model_path, "--controls=" + csv_numbers(shifted_controls(model)))
    for b, (pose, reported) in enumerate(zip(forward.body_poses(), cli["bodies"])):
        np.testing.assert_array_equal(state[b, :4], pose.quaternion)
        np.testing.assert_array_equal(state[b, 4:], pose.position)
        np.testing.assert_allclose(state[b, :4], reported["quaternion"], rtol=0, atol=1e-12)
        # The rotation matrix of the unit quaternion (w, x, y, z), written out.
        w, x, y, z = state[b, :4]
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
        np.testing.assert_allclose(R, pose.rotation, rtol=0, atol=1e-14)


def test_set_state_reads_scalar_first_quaternions():
    """A row [cos(a/2), 0, 0, sin(a/2), ...] turns that body by a about z."""
    model = ccma.load_model(str(MODELS[0]))
    forward = ccma.ForwardProblem(model)
    state = forward.state
    a = 0.3
    state[0, :4] = [np.cos(a / 2), 0, 0, np.sin(a / 2)]
    state[0, 4:] = [0.1, -0.2, 0.7]
    forward.set_state(state)
    pose = forward.body_pose(0)
    np.testing.assert_allclose(pose.rpy, [0, 0, a], rtol=0, atol=1e-15)
    np.testing.assert_allclose(pose.rotation, [[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]],
                               rtol=0, atol=1e-15)
    np.testing.assert_array_equal(pose.position, [0.1, -0.2, 0.7])
    # set_state normalises: a scaled row gives the same rotation.
    state[0, :4] *= 3.0
    forward.set_state(state)
    np.testing.assert_allclose(forward.state[0, :4], [np.cos(a / 2), 0, 0, np.sin(a / 2)], rtol=0, atol=1e-15)


def test_assemble_reports_its_substeps():
    """A 3 cm move in sub-steps of at most 2 cm takes 2 sub-steps."""
    model = ccma.load_model(str(MODELS[0]))
    forward = ccma.ForwardProblem(model, ccma.ForwardOptions(max_control_step=0.02))
    u = model.home_controls.copy()
    for k in range(model.num_bases):
        u[3 * k] += 0.03
    assert forward.assemble(u).substeps == 2
    assert forward.solve(u).substeps == 1


def test_native_and_ceres_solvers_agree(model_path):
    """The native sparse LM (default) and Ceres reach the same assembly."""
    model = ccma.load_model(model_path)
    u = shifted_controls(model)
    native = ccma.ForwardProblem(model)
    ceres = ccma.ForwardProblem(model, ccma.ForwardOptions(solver="ceres"))
    a, b = native.assemble(u), ceres.assemble(u)
    assert a.assembled == b.assembled
    np.testing.assert_allclose(a.end_effector.position, b.end_effector.position, rtol=0, atol=1e-11)
    assert ccma.ForwardOptions().solver == "native"
