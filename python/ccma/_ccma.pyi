"""ccma: simulation and kinematic control of closed-loop mechanisms driven by mobile robots
(Constrained Collaborative Mobile Agents). Units: metres, radians, seconds; E in m^2.

Type stub of the extension module `ccma._ccma` (python/src/*.cc), re-exported by the
package `ccma`. Checked against the built module by python/tests/test_stub.py.
Reference: docs/python.md.
"""
import os
from typing import Any, Literal, Optional, Sequence, Tuple, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._records import Record
from .results import CheckResult, DynamicsResult, PlanResult, RetimeResult, StaticsResult, TrajectoryResult, ViewResult
from ._tables import Table

__version__: str
"""The ccma version, e.g. '0.1.0' (the CMake project version)."""

# ------------------------------------------------------------------ errors ----

class ModelError(ValueError):
    """Raised when a model file (or model text) cannot be read or is not a valid model: by
    load_model, load_model_from_string, and by view, workspace and design_sweep given a model
    file's path. Carries one argument, the message 'file:line: key: what' (str(e), e.args[0]),
    the same text `ccma check` prints."""

class WaypointError(ValueError):
    """Raised by load_waypoints when a waypoint CSV cannot be read or is malformed (a missing
    column, a value that is not a number, time going backwards). Carries one argument, the
    message 'file:line: what' (str(e), e.args[0])."""

class ViewInputError(ValueError):
    """Raised by view and view_html when the trajectory CSV, replay directory or workspace CSV to
    draw cannot be read or is malformed. Carries one argument, the message naming the file, and
    the line and column where there is one: 'file:line: column 'name': what' (str(e), e.args[0])."""

class WorkBoundError(ValueError):
    """Raised by workspace and design when the run is estimated longer than their max_minutes
    (measured on its first seconds; docs/security.md, "Work bounded by its cost"). Carries one
    argument, the message: the estimate, the bound and the max_minutes that would allow it."""

# ------------------------------------------------------------------ models ----

class Body:
    """A rigid body (mobile bases are bodies too). Read-only; not constructible from Python."""

    @property
    def name(self) -> str:
        """The body's name in the model file."""
    @property
    def R_WB_home(self) -> NDArray[np.float64]:
        """Home orientation, 3x3 rotation (world from body)."""
    @property
    def p_WB_home(self) -> NDArray[np.float64]:
        """Home position of the body frame, shape (3,) [m]."""
    @property
    def base_index(self) -> int:
        """Index into Model.mobile_bases, or -1."""
    @property
    def is_mobile_base(self) -> bool:
        """Whether the body is a mobile base (base_index >= 0)."""
    def __repr__(self) -> str:
        """<ccma.Body 'name'>."""

class MobileBase:
    """A mobile base: controls x [m], y [m], theta [rad]; a legged base also height [m], roll, pitch [rad].
    Read-only; not constructible from Python."""

    @property
    def name(self) -> str:
        """The base's name in the model file."""
    @property
    def body(self) -> int:
        """Index into Model.bodies."""
    @property
    def type(self) -> Literal["omni", "differential", "legged"]:
        """'omni', 'differential' or 'legged'."""
    @property
    def control_names(self) -> list[str]:
        """Its controls in the order of u, with units ('x_m', 'y_m', 'theta_rad'; a legged base also
        'height_m', 'roll_rad', 'pitch_rad')."""
    @property
    def body_height(self) -> float:
        """A legged base's home body height [m] (0 for wheeled bases)."""
    @property
    def actuation(self) -> Literal["complete", "reduced"]:
        """'complete' or 'reduced' (reduced: its heading is no control)."""
    @property
    def home_pose(self) -> NDArray[np.float64]:
        """x [m], y [m], theta [rad] at home, shape (3,)."""
    def __repr__(self) -> str:
        """<ccma.MobileBase 'name' type>."""

class Joint:
    """A joint of the passive chain between bodies A and B (-1 = world). Read-only; not constructible."""

    @property
    def name(self) -> str:
        """The joint's name (given, or 'joint<i>' by its index in the file)."""
    @property
    def type(self) -> Literal["revolute", "spherical", "universal", "prismatic", "fixed"]:
        """'revolute', 'spherical', 'universal', 'prismatic' or 'fixed'."""
    @property
    def body_a(self) -> int:
        """Index of body A into Model.bodies, or -1 for the world."""
    @property
    def body_b(self) -> int:
        """Index of body B into Model.bodies, or -1 for the world."""
    @property
    def p_A(self) -> NDArray[np.float64]:
        """Joint point in A's frame, shape (3,) [m]."""
    @property
    def p_B(self) -> NDArray[np.float64]:
        """Joint point in B's frame, shape (3,) [m]."""
    @property
    def a_A(self) -> NDArray[np.float64]:
        """Axis in A's frame (revolute, prismatic, universal's first), shape (3,)."""
    @property
    def a_B(self) -> NDArray[np.float64]:
        """The same axis in B's frame (revolute, prismatic), shape (3,)."""
    @property
    def b_B(self) -> NDArray[np.float64]:
        """Universal: the second axis, in B's frame, shape (3,)."""
    @property
    def actuated(self) -> bool:
        """Its coordinate is a control."""
    @property
    def control(self) -> int:
        """Index into the controls when actuated, else -1."""
    @property
    def limited(self) -> bool:
        """Whether lower <= q <= upper applies."""
    @property
    def lower(self) -> float:
        """Lower limit [rad or m] when limited."""
    @property
    def upper(self) -> float:
        """Upper limit [rad or m] when limited."""
    @property
    def q_home(self) -> float:
        """The coordinate's value at home [rad or m] (0 unless the file gives q_home)."""
    @property
    def line(self) -> int:
        """Line in the model file."""
    @property
    def has_coordinate(self) -> bool:
        """Revolute and prismatic joints have a coordinate q."""
    def __repr__(self) -> str:
        """<ccma.Joint 'name' type>."""

class EndEffectorSpec:
    """Where the end-effector is and what is controlled. Read-only; not constructible from Python."""

    @property
    def body(self) -> int:
        """Index into Model.bodies."""
    @property
    def p_B(self) -> NDArray[np.float64]:
        """The point in the body's frame, shape (3,) [m]."""
    @property
    def p_W_home(self) -> NDArray[np.float64]:
        """The point in world at home, shape (3,) [m]."""
    @property
    def controlled(self) -> list[str]:
        """Controlled components, e.g. ['x', 'y', 'z', 'yaw'] (of x y z roll pitch yaw)."""

class Model:
    """A loaded mechanism (ccma.load_model): constant, shared by every problem built on it.

    Controls: 3 per mobile base (x [m], y [m], theta [rad]), then one per actuated joint [rad or m].
    """

    @property
    def name(self) -> str:
        """The model's name."""
    @property
    def description(self) -> str:
        """The model's description ('' if none)."""
    @property
    def source(self) -> str:
        """The file it was loaded from (the source_name for load_model_from_string)."""
    @property
    def bodies(self) -> list[Body]:
        """Every body in file order: `bodies` first, then the mobile bases."""
    @property
    def mobile_bases(self) -> list[MobileBase]:
        """The mobile bases in file order."""
    @property
    def joints(self) -> list[Joint]:
        """The joints in file order."""
    @property
    def end_effector(self) -> EndEffectorSpec:
        """Where the end-effector is and which components are controlled."""
    @property
    def num_bodies(self) -> int:
        """Number of bodies (rows of a state array)."""
    @property
    def num_bases(self) -> int:
        """Number of mobile bases."""
    @property
    def num_controls(self) -> int:
        """3 per mobile base (6 per legged base) plus one per actuated joint."""
    def base_control(self, k: int) -> int:
        """Index into the controls of base k's x (its block: len(mobile_bases[k].control_names) values)."""
    @property
    def num_constraints(self) -> int:
        """Rows of C (joints + 9 per base)."""
    @property
    def state_size(self) -> int:
        """6 per body (tangent size): rotation increment [rad] then translation [m] per body."""
    @property
    def home_controls(self) -> NDArray[np.float64]:
        """Controls at home, shape (num_controls,) (a new writable array on every access)."""
    @property
    def effective_control_indices(self) -> list[int]:
        """Indices of the controls the control solver may change."""
    @property
    def controlled(self) -> list[str]:
        """Controlled end-effector components, e.g. ['x', 'y', 'z', 'yaw'] (= end_effector.controlled)."""
    def find_body(self, name: str) -> int:
        """Index of the body named `name`, or -1."""
    def find_joint(self, name: str) -> int:
        """Index of the joint named `name`, or -1."""
    def __repr__(self) -> str:
        """<ccma.Model 'name': N bodies, N bases, N joints>."""

def load_model(path: str, obstacles: str | None = None) -> Model:
    """Reads and validates a model file (YAML or JSON); raises ModelError 'file:line: key: what' (a misspelt key too); other unknown keys, lengths above 100 m and angles above 2 pi warn (UserWarning). obstacles: a file with one key, obstacles:, added to the model's."""

def load_model_from_string(text: str, source_name: str = "<string>") -> Model:
    """load_model for model text in memory; source_name stands in for the file name in messages."""

# ----------------------------------------------------------------- forward ----

class EndEffectorPose:
    """The end-effector pose X_EE. Read-only; not constructible from Python."""

    @property
    def position(self) -> NDArray[np.float64]:
        """p_WE: the controlled point in world, shape (3,) [m]."""
    @property
    def rotation(self) -> NDArray[np.float64]:
        """R_EE = R_WB(now) R_WB(home)^T, world axes (3x3)."""
    @property
    def rpy(self) -> NDArray[np.float64]:
        """The rotation as [roll, pitch, yaw], shape (3,) [rad]."""
    def __repr__(self) -> str:
        """<ccma.EndEffectorPose position=[x, y, z]>."""

class BodyPose:
    """One body's absolute pose. Read-only; not constructible from Python."""

    @property
    def name(self) -> str:
        """The body's name."""
    @property
    def position(self) -> NDArray[np.float64]:
        """p_WB, shape (3,) [m]."""
    @property
    def rotation(self) -> NDArray[np.float64]:
        """R_WB (3x3)."""
    @property
    def quaternion(self) -> NDArray[np.float64]:
        """R_WB as a unit quaternion [w, x, y, z] (scalar first, as in ForwardProblem.state and the CLI)."""
    @property
    def rpy(self) -> NDArray[np.float64]:
        """R_WB as [roll, pitch, yaw], shape (3,) [rad]."""

class JointCoordinate:
    """q of a revolute [rad] or prismatic [m] joint. Read-only; not constructible from Python."""

    @property
    def joint(self) -> int:
        """Index into Model.joints."""
    @property
    def q(self) -> float:
        """The coordinate [rad or m], 0 at home."""
    @property
    def within_limits(self) -> bool:
        """lower <= q <= upper within 1e-9 (True without limits)."""

class ForwardOptions:
    """Options of the forward solve (problems/forward_problem.h); every field is a keyword of the constructor."""

    def __init__(
        self,
        *,
        solver: Literal["native", "ceres"] = "native",
        secant_predictor: bool = True,
        rigid_motion_predictor: bool = True,
        assembly_tolerance: float = 1e-16,
        max_iterations: int = 100,
        max_control_step: float = 0.02,
        max_newton_polish_steps: int = 8,
        branch_jump_relative: float = 0.5,
        branch_jump_absolute: float = 0.01,
    ) -> None:
        """Defaults, overridden by the given fields (an unknown keyword raises TypeError)."""
    @property
    def solver(self) -> Literal["native", "ceres"]:
        """'native' (ccma's sparse Levenberg-Marquardt, default) or 'ceres' (ceres::Solve, the reference)."""
    @solver.setter
    def solver(self, value: Literal["native", "ceres"]) -> None: ...
    @property
    def secant_predictor(self) -> bool:
        """Start each solve from the secant prediction along a path (default True)."""
    @secant_predictor.setter
    def secant_predictor(self, value: bool) -> None: ...
    @property
    def rigid_motion_predictor(self) -> bool:
        """When every base moves by one planar rigid motion (and no joint ends at the ground), move every body by it: the solve ends without an iteration (default True)."""
    @rigid_motion_predictor.setter
    def rigid_motion_predictor(self, value: bool) -> None: ...
    @property
    def assembly_tolerance(self) -> float:
        """E [m^2] below which the mechanism counts as assembled (default 1e-16)."""
    @assembly_tolerance.setter
    def assembly_tolerance(self, value: float) -> None: ...
    @property
    def max_iterations(self) -> int:
        """Solver iterations per solve (per sub-step in assemble()), default 100."""
    @max_iterations.setter
    def max_iterations(self, value: int) -> None: ...
    @property
    def max_control_step(self) -> float:
        """assemble(): largest control change per sub-step [m, rad] (max-norm), default 0.02."""
    @max_control_step.setter
    def max_control_step(self, value: float) -> None: ...
    @property
    def max_newton_polish_steps(self) -> int:
        """Exact-Newton steps on E after the solver when E stays above the tolerance, default 8."""
    @max_newton_polish_steps.setter
    def max_newton_polish_steps(self, value: int) -> None: ...
    @property
    def branch_jump_relative(self) -> float:
        """Branch jump when |s - (s + ds/du du)| > relative * |ds/du du| + absolute; default 0.5."""
    @branch_jump_relative.setter
    def branch_jump_relative(self, value: float) -> None: ...
    @property
    def branch_jump_absolute(self) -> float:
        """The absolute part of that threshold [m, rad], default 0.01."""
    @branch_jump_absolute.setter
    def branch_jump_absolute(self, value: float) -> None: ...
    def is_valid(self) -> Tuple[bool, str]:
        """(ok, why): whether every field is in range; why names the field and its range ('' if ok)."""

class ForwardResult:
    """The outcome of ForwardProblem.solve/assemble (and ControlProblem.set_controls). Read-only.

    The attributes of `ccma simulate`'s JSON, by its keys (to_dict() is that JSON), and the
    solver's details (newton_steps, gradient_norm, branch_jump_size, ...). Keeps its problem alive."""

    @property
    def converged(self) -> bool:
        """dE/ds ~ 0 (the solver converged)."""
    @property
    def assembled(self) -> bool:
        """E below the assembly tolerance."""
    @property
    def residual_energy(self) -> float:
        """E(s_hat, u) [m^2]."""
    @property
    def iterations(self) -> int:
        """Solver iterations, summed over sub-steps."""
    @property
    def substeps(self) -> int:
        """Solves made (assemble() may split the step)."""
    @property
    def newton_steps(self) -> int:
        """Exact-Newton polish steps after the solver (E > 0)."""
    @property
    def gradient_norm(self) -> float:
        """max |dE/ds| at the end."""
    @property
    def gradient_norm_is_bound(self) -> bool:
        """gradient_norm is the upper bound 2 |J|_F |C|, not the value: an
        assembled state moved rigidly with its bases, checked on its residuals only."""
    @property
    def solve_time_ms(self) -> float:
        """Wall time of the solve(s) [ms]."""
    @property
    def branch_jump(self) -> bool:
        """assemble(): some sub-step left the branch its predictor followed."""
    @property
    def branch_jump_size(self) -> float:
        """The largest deviation from the prediction [m or rad]."""
    @property
    def branch_jump_substep(self) -> int:
        """The sub-step of that deviation (-1 if none)."""
    @property
    def message(self) -> str:
        """The solver's termination message (last solve)."""
    @property
    def end_effector(self) -> EndEffectorPose:
        """The end-effector pose after the solve."""
    @property
    def controls(self) -> NDArray[np.float64]:
        """The controls solved at, shape (num_controls,)."""
    def __repr__(self) -> str:
        """<ccma.ForwardResult assembled=... residual_energy=... iterations=...>."""
    @property
    def model(self) -> str:
        """The model's name."""
    @property
    def assembly_tolerance(self) -> float:
        """E [m^2] below which the mechanism counts as assembled."""
    @property
    def start(self) -> Literal["home", "current"]:
        """'home': the solve started from the home configuration; 'current': from the problem's configuration before the call."""
    @property
    def bodies(self) -> list[BodyPose]:
        """Every body's absolute pose after the solve (name, position [m], rpy [rad], quaternion)."""
    @property
    def joints(self) -> list[Record]:
        """Every revolute and prismatic joint: Record {name, type, q [rad or m], actuated, limits?}."""
    @property
    def limits_violated(self) -> list[str]:
        """Names of the joints outside their limits."""
    @property
    def clearance(self) -> Optional[Record]:
        """Record {min [m], pair, margin [m], below_margin}; None without collision geometry."""
    @property
    def deflection(self) -> Optional[Record]:
        """assemble(loaded=True): Record {end_effector [dx, dy, dz [m], rx, ry, rz [rad]], max_body_m [m], held}; None otherwise."""
    @property
    def loaded(self) -> Optional[Record]:
        """assemble(loaded=True): Record {converged, iterations, load_fraction, unbalanced_load [N or N*m], yields [m or rad per control]}; None otherwise."""
    @property
    def warning(self) -> str:
        """Not assembled, not converged, a branch jump ('' when nothing went wrong)."""
    def to_dict(self) -> dict[str, Any]:
        """The JSON document `ccma simulate` prints for the same solve (same keys and values)."""

class ForwardProblem:
    """Simulation: s_hat(u) = argmin_s E(s, u), warm-started from the last state.

    Keeps the model alive. One thread at a time: any call while another thread is inside one
    of this problem's raises RuntimeError ("ccma.ForwardProblem is being used by another thread;
    use one problem per thread").
    """

    def __init__(self, model: Model, options: ForwardOptions = ...) -> None:
        """A problem at the home state and home controls; raises ValueError on invalid options."""
    def solve(self, u: ArrayLike) -> ForwardResult:
        """One warm-started solve at controls u, shape (num_controls,) [m, rad]; ValueError on a wrong size or non-finite entry."""
    def assemble(self, u: ArrayLike, loaded: bool = False, wrench: Optional[ArrayLike] = None) -> ForwardResult:
        """Moves the controls to u in sub-steps of at most max_control_step [m, rad], following the branch; reports a branch jump.

        loaded=True (`ccma simulate --loaded`, a model with stiffness keys): the result is the nonlinear
        loaded equilibrium under gravity, the payload and wrench [fx, fy, fz [N], mx, my, mz [N*m]]:
        state, end_effector, bodies and joints are the loaded ones, with deflection and loaded; the
        problem itself stays at the rigid assembly. ValueError for a wrench without loaded=True."""
    def reset_to_home(self) -> None:
        """Home state and home controls (no solve)."""
    @property
    def state(self) -> NDArray[np.float64]:
        """(num_bodies x 7) array, rows [qw, qx, qy, qz, px, py, pz]: the unit quaternion of R_WB, scalar first, then p_WB [m] (a copy)."""
    def set_state(self, state: ArrayLike) -> None:
        """Replaces the state ((num_bodies x 7), rows [qw, qx, qy, qz, px, py, pz] as .state; quaternions normalised) without solving."""
    @property
    def controls(self) -> NDArray[np.float64]:
        """Current controls, shape (num_controls,) (read-only; a live view: copy it to keep it)."""
    @property
    def end_effector(self) -> EndEffectorPose:
        """The end-effector pose at the current state."""
    def energy(self) -> float:
        """E at the current state and controls [m^2]."""
    @overload
    def body_pose(self, body: int) -> BodyPose:
        """The absolute pose of body number `body` (IndexError if out of range)."""
    @overload
    def body_pose(self, name: str) -> BodyPose:
        """The absolute pose of the body named `name` (KeyError if there is none)."""
    def body_poses(self) -> list[BodyPose]:
        """Every body's absolute pose, in model order."""
    def joint_coordinates(self) -> list[JointCoordinate]:
        """q of every revolute [rad] and prismatic [m] joint, in file order."""
    def limits_violated(self) -> list[str]:
        """Names of the joints outside their limits."""
    def end_effector_state_jacobian(self) -> NDArray[np.float64]:
        """dX_EE/ds (6 x state_size): rows position [m] then rotation increment [rad]."""

# ----------------------------------------------------------------- control ----

class ControlOptions:
    """Options of the control solve (problems/control_problem.h); every field is a keyword of the constructor."""

    def __init__(
        self,
        *,
        method: Literal["lm", "bfgs"] = "lm",
        gradient: Literal["implicit", "finite_difference"] = "implicit",
        lambda_: float = 0.5,
        max_step_m: float = 0.01,
        max_step_rad: float = 0.005,
        max_iterations: int = 100,
        target_tolerance: float = 1e-10,
        finite_difference_step: float = 1e-6,
        forward: ForwardOptions = ...,
        singularity_weight: float = 0.0,
        singularity_threshold: float = 0.1,
        pivot_weight: float = 0.0,
        pivot_threshold: float = 0.001,
        spread_weight: float = 0.0,
        clearance_m: float = 0.5,
        travel_weight: float = 0.0,
    ) -> None:
        """Defaults, overridden by the given fields, e.g. ControlOptions(method='bfgs') (unknown keyword: TypeError)."""
    @property
    def method(self) -> Literal["lm", "bfgs"]:
        """'lm' (Levenberg-Marquardt, default) or 'bfgs' (the paper's); ValueError for anything else."""
    @method.setter
    def method(self, value: Literal["lm", "bfgs"]) -> None: ...
    @property
    def gradient(self) -> Literal["implicit", "finite_difference"]:
        """'implicit' (sensitivities, default) or 'finite_difference'; ValueError for anything else."""
    @gradient.setter
    def gradient(self, value: Literal["implicit", "finite_difference"]) -> None: ...
    @property
    def lambda_(self) -> float:
        """Weight of E in the objective, 0 < lambda < 1 (default 0.5): the flag --lambda (a Python keyword, hence the underscore)."""
    @lambda_.setter
    def lambda_(self, value: float) -> None: ...
    @property
    def max_step_m(self) -> float:
        """Path step: end-effector translation per step [m] (default 0.01)."""
    @max_step_m.setter
    def max_step_m(self, value: float) -> None: ...
    @property
    def max_step_rad(self) -> float:
        """Path step: end-effector rotation per step [rad] (default 0.005)."""
    @max_step_rad.setter
    def max_step_rad(self, value: float) -> None: ...
    @property
    def max_iterations(self) -> int:
        """Outer iterations per step (default 100)."""
    @max_iterations.setter
    def max_iterations(self, value: int) -> None: ...
    @property
    def target_tolerance(self) -> float:
        """A step is reached when every controlled component is within this [m or rad] (default 1e-10)."""
    @target_tolerance.setter
    def target_tolerance(self, value: float) -> None: ...
    @property
    def finite_difference_step(self) -> float:
        """Step of gradient='finite_difference' [m or rad] (default 1e-6)."""
    @finite_difference_step.setter
    def finite_difference_step(self, value: float) -> None: ...
    @property
    def singularity_weight(self) -> float:
        """Weight of the barrier on the smallest singular value of dX/du, in the null space of the end-effector task; 0 = off (default) [1]."""
    @singularity_weight.setter
    def singularity_weight(self, value: float) -> None: ...
    @property
    def singularity_threshold(self) -> float:
        """sigma_0: the barrier acts below this smallest singular value of dX/du [m or rad per control unit] (default 0.1)."""
    @singularity_threshold.setter
    def singularity_threshold(self, value: float) -> None: ...
    @property
    def pivot_weight(self) -> float:
        """Weight of the barrier on the pivot ratios of dG/ds, in the null space of the end-effector task; 0 = off (default) [1]."""
    @pivot_weight.setter
    def pivot_weight(self, value: float) -> None: ...
    @property
    def pivot_threshold(self) -> float:
        """rho_0: that barrier acts on every pivot ratio of dG/ds below this [1] (default 0.001)."""
    @pivot_threshold.setter
    def pivot_threshold(self, value: float) -> None: ...
    @property
    def spread_weight(self) -> float:
        """Weight of keeping bases clearance_m apart, in the null space of the end-effector task; 0 = off (default) [1/m^2]."""
    @spread_weight.setter
    def spread_weight(self, value: float) -> None: ...
    @property
    def clearance_m(self) -> float:
        """Horizontal base-to-base distance below which spread_weight pushes bases apart [m] (default 0.5)."""
    @clearance_m.setter
    def clearance_m(self, value: float) -> None: ...
    @property
    def travel_weight(self) -> float:
        """Weight of least base travel from the start of move_to, in the null space of the end-effector task; 0 = off (default) [1/m^2]."""
    @travel_weight.setter
    def travel_weight(self, value: float) -> None: ...
    @property
    def forward(self) -> ForwardOptions:
        """ForwardOptions of the inner solves (a reference: options.forward.max_iterations = 50 works)."""
    @forward.setter
    def forward(self, value: ForwardOptions) -> None: ...
    def is_valid(self) -> Tuple[bool, str]:
        """(ok, why): whether every field (including forward) is in range; why names the field ('' if ok)."""

class ControlStepResult:
    """One solve toward one target (ControlProblem.step). Read-only."""

    @property
    def reached(self) -> bool:
        """The target is within tolerance and the mechanism assembled."""
    @property
    def assembled(self) -> bool:
        """E below the assembly tolerance at the returned controls."""
    @property
    def singular(self) -> bool:
        """dG/ds was singular at some accepted point."""
    @property
    def iterations(self) -> int:
        """Outer iterations."""
    @property
    def forward_solves(self) -> int:
        """Forward solves made."""
    @property
    def objective(self) -> float:
        """O = 1/2 |e|^2 + lambda E at the returned controls."""
    @property
    def error(self) -> float:
        """max |e| over the controlled components [m, rad]."""
    @property
    def residual_energy(self) -> float:
        """E at the returned controls [m^2]."""
    @property
    def dG_ds_pivot_ratio(self) -> float:
        """Pivot ratio of dG/ds at the last linearisation [1]."""
    @property
    def min_singular_value_dX_du(self) -> float:
        """Smallest singular value of dX_controlled/du_effective [m or rad per control unit]; 0 at the workspace edge."""
    @property
    def max_limit_violation(self) -> float:
        """Largest joint limit violation [rad or m]."""
    @property
    def max_effort_violation(self) -> float:
        """[N or N*m]"""
    @property
    def max_clearance_violation(self) -> float:
        """How far a pair of shapes is below collision.margin [m] (0)."""
    @property
    def max_lateral_displacement(self) -> float:
        """Largest lateral displacement of a differential base over the step [m]."""
    @property
    def limited_by(self) -> str:
        """The joints held at a limit when the step ended ('' if none)."""
    @property
    def solve_time_ms(self) -> float:
        """Wall time of the step [ms]."""

class ControlResult:
    """The outcome of ControlProblem.move_to. Read-only.

    The attributes of `ccma control`'s JSON, by its keys (to_dict() is that JSON), and the step
    constraints' measures (max_limit_violation, ...). Keeps its problem alive."""

    @property
    def converged(self) -> bool:
        """The target was reached."""
    @property
    def assembled(self) -> bool:
        """E below the assembly tolerance at the end."""
    @property
    def steps(self) -> int:
        """Path steps taken."""
    @property
    def iterations(self) -> int:
        """Outer iterations, all steps."""
    @property
    def forward_solves(self) -> int:
        """Forward solves, all steps."""
    @property
    def objective(self) -> float:
        """O at the end."""
    @property
    def error(self) -> float:
        """max |e| over the controlled components at the end [m, rad]."""
    @property
    def residual_energy(self) -> float:
        """E at the end [m^2]."""
    @property
    def max_step_residual_energy(self) -> float:
        """The worst E over the path's steps [m^2]."""
    @property
    def branch_jumps_rejected(self) -> int:
        """Trial solves rejected for landing on another assembly branch."""
    @property
    def max_limit_violation(self) -> float:
        """The worst joint limit violation over the path's steps [rad or m]."""
    @property
    def max_effort_violation(self) -> float:
        """[N or N*m]"""
    @property
    def max_clearance_violation(self) -> float:
        """The worst clearance below collision.margin over the path's steps [m] (0)."""
    @property
    def max_lateral_displacement(self) -> float:
        """The worst lateral displacement of a differential base over the path's steps [m]."""
    @property
    def limited_by(self) -> str:
        """The joints at a limit when it stopped ('' if none)."""
    @property
    def solve_time_ms(self) -> float:
        """Wall time [ms]."""
    @property
    def target(self) -> NDArray[np.float64]:
        """The target [x, y, z, roll, pitch, yaw], shape (6,) [m, rad]."""
    @property
    def controls(self) -> NDArray[np.float64]:
        """All controls at the end, shape (num_controls,)."""
    @property
    def end_effector(self) -> EndEffectorPose:
        """The pose assembled at `controls`."""
    def __repr__(self) -> str:
        """<ccma.ControlResult converged=... steps=... error=...>."""
    @property
    def model(self) -> str:
        """The model's name."""
    @property
    def method(self) -> Literal["lm", "bfgs"]:
        """The control method."""
    @property
    def conditioning(self) -> Record:
        """Record {dG_ds_pivot_ratio, min_dG_ds_pivot_ratio_on_path [1], min_singular_value_dX_du, min_singular_value_dX_du_on_path [m or rad per control unit]}."""
    @property
    def secondary(self) -> Optional[Record]:
        """The null-space objective's weights, null_space_steps and objective; None when off."""
    @property
    def bodies(self) -> list[BodyPose]:
        """Every body's absolute pose at the end."""
    @property
    def joints(self) -> list[Record]:
        """Every revolute and prismatic joint: Record {name, type, q [rad or m], actuated, limits?}."""
    @property
    def limits_violated(self) -> list[str]:
        """Names of the joints outside their limits."""
    @property
    def clearance(self) -> Optional[Record]:
        """Record {min [m], pair, margin [m], below_margin}; None without collision geometry."""
    @property
    def from_home(self) -> Record:
        """Record {reproducible, end_effector_distance_m [m], max_state_difference}: the controls assembled from home give this configuration (checked when first asked for)."""
    @property
    def compensation(self) -> Optional[Record]:
        """move_to(compensate=True): Record {converged, rounds, miss [m or rad], aim [x, y, z, roll, pitch, yaw], rigid_end_effector}; None otherwise."""
    @property
    def deflection(self) -> Optional[Record]:
        """move_to(compensate=True): the loaded configuration's deflection, as ForwardResult.deflection; None otherwise."""
    @property
    def warning(self) -> str:
        """Why the target was not reached, or that the controls assemble elsewhere from home ('' when neither)."""
    def to_dict(self) -> dict[str, Any]:
        """The JSON document `ccma control` prints for the same move (same keys and values)."""

class ControlProblem:
    """Kinematic control: controls u whose assembly puts the end-effector at a target.

    min 1/2 |e|^2 + lambda E, gradients from implicit sensitivities. Keeps the model alive.
    One thread at a time: any call while another thread is inside one of this problem's (or of
    its forward problem's) raises RuntimeError ("ccma.ControlProblem is being used by another
    thread; use one problem per thread").
    """

    def __init__(self, model: Model, options: ControlOptions = ...) -> None:
        """A problem starting at home; raises ValueError on invalid options."""
    def set_controls(self, u: ArrayLike) -> ForwardResult:
        """Assembles the mechanism at u, shape (num_controls,) [m, rad] (following the branch) and starts from there."""
    def step(self, target: ArrayLike) -> ControlStepResult:
        """One solve toward target [x, y, z, roll, pitch, yaw] ([m], [rad]), or only the controlled components, without path splitting (small moves)."""
    def move_to(self, target: ArrayLike, compensate: bool = False, wrench: Optional[ArrayLike] = None) -> ControlResult:
        """Walks the end-effector to target in steps of max_step_m / max_step_rad.

        compensate=True (`ccma control --compensate`, a model with stiffness keys): the controls put
        the loaded end-effector (under gravity, the payload and wrench [fx, fy, fz [N], mx, my, mz
        [N*m]]) on the target; end_effector, error, converged, bodies and joints are then the loaded
        ones, and compensation and deflection say how.

        target: [x, y, z, roll, pitch, yaw] ([m], [rad]), or one value per component of
        model.controlled in that order (as `ccma control --target`, e.g. [x, y, z, yaw] on a 4dof
        model); components not controlled are ignored. ValueError on any other length."""
    @overload
    def follow(self, waypoints: Sequence[Waypoint], out: Optional[str | os.PathLike[str]] = None,
               compensate: bool = False, wrench: Optional[ArrayLike] = None) -> TrajectoryResult:
        """`ccma trajectory`: follows ccma.Waypoint's (e.g. load_waypoints(path)) from the current controls; stops at the first unreachable one.

        Returns a ccma.TrajectoryResult (the command's JSON as attributes, its CSV as `table`);
        out=PATH writes the CSV too. ValueError (naming the waypoint) on a time not finite,
        beyond 1e6 s, or smaller than the one before. compensate=True (`ccma trajectory
        --compensate`, a model with stiffness keys): every step puts the loaded end-effector
        (gravity, payload and wrench [fx, fy, fz [N], mx, my, mz [N*m]]) on its target; the rows,
        end_effector and clearance are the loaded ones, and `compensation` is
        {rounds, max_miss [m or rad]}."""
    @overload
    def follow(self, waypoints: ArrayLike, out: Optional[str | os.PathLike[str]] = None,
               compensate: bool = False, wrench: Optional[ArrayLike] = None) -> TrajectoryResult:
        """The same for an (N x 7) array of rows [time [s], x, y, z [m], roll, pitch, yaw [rad]]."""
    def objective(self, target: ArrayLike) -> Tuple[float, NDArray[np.float64]]:
        """(O, dO/du_eff) at the current controls for target (6 values, or the controlled components); the gradient over the effective controls.

        ValueError on a target entry not finite or beyond 1e4."""
    def state_sensitivity(self) -> NDArray[np.float64]:
        """ds/du: (state_size x effective controls) at the current solution (m or rad per control unit)."""
    def end_effector_jacobian(self) -> NDArray[np.float64]:
        """dX_EE/du: (6 x effective controls), rows x y z [m] then rotation increment [rad]."""
    @property
    def controls(self) -> NDArray[np.float64]:
        """Current controls, shape (num_controls,) (read-only; a live view: copy it to keep it)."""
    @property
    def effective_controls(self) -> list[int]:
        """Indices into controls that the solver changes (columns of the sensitivities)."""
    @property
    def forward(self) -> ForwardProblem:
        """The inner ForwardProblem (state, body poses); valid while this problem lives."""
    @property
    def current_pose(self) -> NDArray[np.float64]:
        """[x, y, z, roll, pitch, yaw] of the end-effector now, shape (6,) [m, rad]."""

# --------------------------------------------------------------- collision ----

@overload
def clearance(problem: ForwardProblem) -> Record | None:
    """The smallest clearance at the problem's configuration, as `ccma simulate`'s: Record {min [m], pair, margin [m], below_margin}, or None without collision geometry."""
@overload
def clearance(problem: ControlProblem) -> Record | None:
    """The same for a ControlProblem."""
def plan(
    problem: ControlProblem,
    waypoints: Sequence[Waypoint],
    path_weight: float = 0.01,
    smoothness_weight: float = 1.0,
    travel_weight: float = 0.01,
    plan_iterations: int = 200,
    plan_time_s: float = 120.0,
    out: Optional[str | os.PathLike[str]] = None,
) -> PlanResult:
    """`ccma plan` (whole-trajectory planning): the command's JSON as attributes (converged, used, iterations, greedy, plan, controls, end_effector, clearance, warning), its CSV as `table`; out=PATH writes the CSV."""

# ----------------------------------------------------------------- statics ----

@overload
def statics(
    problem: ForwardProblem, wrench: ArrayLike | None = None, mocap_noise_m: float = 0.001, mocap_noise_rad: float = 0.003
) -> StaticsResult:
    """`ccma statics`: joint reactions and control efforts at the problem's configuration (the command's JSON as attributes)."""
@overload
def statics(
    problem: ControlProblem, wrench: ArrayLike | None = None, mocap_noise_m: float = 0.001, mocap_noise_rad: float = 0.003
) -> StaticsResult:
    """The same for a ControlProblem."""

# -------------------------------------------------------- dynamics, retime ----

@overload
def dynamics(
    problem: ForwardProblem,
    trajectory: str | os.PathLike[str] | Table | TrajectoryResult | PlanResult,
    wrench: ArrayLike | None = None,
    out: Optional[str | os.PathLike[str]] = None,
) -> DynamicsResult:
    """`ccma dynamics`: inverse dynamics along a trajectory (a CSV path, a ccma.Table, or follow's / plan's result): the command's JSON as attributes, its --out CSV as `table`; out=PATH writes it."""
@overload
def dynamics(
    problem: ControlProblem,
    trajectory: str | os.PathLike[str] | Table | TrajectoryResult | PlanResult,
    wrench: ArrayLike | None = None,
    out: Optional[str | os.PathLike[str]] = None,
) -> DynamicsResult:
    """The same for a ControlProblem."""
@overload
def retime(
    problem: ForwardProblem,
    trajectory: str | os.PathLike[str] | Table | TrajectoryResult | PlanResult,
    out: Optional[str | os.PathLike[str]] = None,
) -> RetimeResult:
    """`ccma retime`: the fastest rest-to-rest timing of the trajectory's path within every limit: the command's JSON as attributes, the retimed CSV as `table` and `csv_text`; out=PATH writes it when feasible."""
@overload
def retime(
    problem: ControlProblem,
    trajectory: str | os.PathLike[str] | Table | TrajectoryResult | PlanResult,
    out: Optional[str | os.PathLike[str]] = None,
) -> RetimeResult:
    """The same for a ControlProblem."""

# --------------------------------------------------------------- waypoints ----

class Waypoint:
    """An end-effector waypoint: time [s], position [m], rpy [rad]."""

    def __init__(self, time: float, position: ArrayLike, rpy: ArrayLike = ...) -> None:
        """A waypoint at `time` [s], position (3,) [m] and rpy (3,) [rad] (default zeros)."""
    @property
    def time(self) -> float:
        """Time [s]."""
    @time.setter
    def time(self, value: float) -> None: ...
    @property
    def position(self) -> NDArray[np.float64]:
        """Position x, y, z, shape (3,) [m] (read-only array; assign a whole new one)."""
    @position.setter
    def position(self, value: ArrayLike) -> None: ...
    @property
    def rpy(self) -> NDArray[np.float64]:
        """Orientation roll, pitch, yaw, shape (3,) [rad] (read-only array; assign a whole new one)."""
    @rpy.setter
    def rpy(self, value: ArrayLike) -> None: ...

def load_waypoints(path: str) -> list[Waypoint]:
    """Reads a waypoint CSV (time,x,y,z,roll,pitch,yaw; s, m, rad; docs/waypoints.md); raises WaypointError."""

# ---------------------------------------------------------------- analysis ----

class FreeMotion:
    """One free motion with the controls fixed (analyses/mobility.h). Read-only."""

    @property
    def direction(self) -> NDArray[np.float64]:
        """ds (state_size): 6 per body, rotation increment [rad] then translation [m]; unit norm."""
    @property
    def bodies(self) -> list[str]:
        """Names of the bodies it moves, in model order (as `ccma check`'s free_motions)."""
    @property
    def joints(self) -> list[str]:
        """Names of the revolute and prismatic joints whose coordinate it changes, in model order (as `ccma check`'s free_motions)."""

class MobilityReport:
    """Numerical mobility at a configuration (analyses/mobility.h, `ccma check`). Read-only."""

    @property
    def constraints(self) -> int:
        """Rows of C."""
    @property
    def constraint_rank(self) -> int:
        """Rank of dC/ds (controls fixed)."""
    @property
    def dof_with_controls_fixed(self) -> int:
        """state_size - constraint_rank: free motions with the controls fixed."""
    @property
    def rigid_with_controls_fixed(self) -> bool:
        """No free motion with the controls fixed."""
    @property
    def dof_with_controls_free(self) -> int:
        """Free motions (ds, du_effective) when the effective controls move too."""
    @property
    def end_effector_dof(self) -> int:
        """Rank of dX_EE over those motions: how many end-effector DOF the controls drive."""
    @property
    def end_effector_dof_nonholonomic(self) -> int:
        """The same when differential bases may only move along their heading."""
    @property
    def smallest_singular_value(self) -> float:
        """Of dC/ds; ~0 means singular."""
    @property
    def residual_energy(self) -> float:
        """E(s, u) [m^2]."""
    @property
    def free_motions(self) -> list[FreeMotion]:
        """A basis of the free motions with the controls fixed, each naming few bodies; empty when rigid."""
    @property
    def free_motions_listed(self) -> bool:
        """False when free motions exist but were too many to list (then free_motions is empty)."""

def analyze_mobility(
    model: Model,
    state: Optional[ArrayLike] = None,
    controls: Optional[ArrayLike] = None,
    rank_tolerance: float = 1e-8,
) -> MobilityReport:
    """Ranks of dC/ds and of the end-effector motions at a state ((num_bodies x 7), rows [qw, qx, qy, qz, px, py, pz] as ForwardProblem.state; default home) and controls (default home)."""

def check(model: Model) -> CheckResult:
    """`ccma check`: the model's counts and its mobility at home (the command's JSON as attributes; to_dict() is that JSON)."""

# ------------------------------------------------------------------ design ----

def design_parameter_sensitivity(
    model: Model,
    state: ArrayLike,
    controls: ArrayLike,
    vary: Sequence[str] = ...,
    vary_length: Sequence[str] = ...,
) -> dict:
    """ds/dp (state tangent per m), dX_EE/dp (6 x P) and dG/dp at a forward solution (state: (num_bodies x 7),
    rows [qw, qx, qy, qz, px, py, pz] as ForwardProblem.state) for the named parameters ('JOINT.x', '.y', '.z', '.point'; 'ANCHOR:JOINT' lengths); keys parameters, ds_dp,
    dX_dp, dG_dp, rcond (docs/design.md). ValueError for an unknown name or a singular dG/ds."""

def evaluate_design(
    model: Model,
    targets: ArrayLike,
    values: ArrayLike,
    vary: Sequence[str] = ...,
    vary_length: Sequence[str] = ...,
    target_tolerance: float = 1e-6,
) -> list[dict]:
    """Reachability of targets (N x 6) on the model with the named parameters set to `values` [m]:
    per target reached, error, min_singular_value, within_limits, controls (docs/design.md)."""

# ------------------------------------------------------------------ replay ----

class ReplayOptions:
    """Options of ccma.replay (execution/replay.h); every field is a keyword of the constructor."""

    def __init__(
        self,
        *,
        noise: Literal["default", "none"] = "default",
        seed: int = 1,
        output_hz: float = 20.0,
        settle_s: float = 1.0,
        torn_residual_energy: float = 1e-5,
        control: ControlOptions = ...,
        gait_hz: float = 2.0,
        gait_bob_m: float = 0.01,
        gait_sway_rad: float = 0.02,
    ) -> None:
        """Defaults, overridden by the given fields, e.g. ReplayOptions(noise='none', seed=3) (unknown keyword: TypeError)."""
    @property
    def noise(self) -> Literal["default", "none", "custom"]:
        """The simulated imperfections: 'default' (docs/cli.md, replay) or 'none' ('custom' is never set from Python)."""
    @noise.setter
    def noise(self, value: Literal["default", "none"]) -> None: ...
    @property
    def seed(self) -> int:
        """Seed of every random draw (noise, slip); the same seed gives the same run."""
    @seed.setter
    def seed(self, value: int) -> None: ...
    def is_valid(self) -> Tuple[bool, str]:
        """(ok, why): whether every field is in range (why names the field and its unit)."""
    @property
    def output_hz(self) -> float:
        """Output samples per second [Hz], in [0.1, 1000]."""
    @output_hz.setter
    def output_hz(self, value: float) -> None: ...
    @property
    def gait_hz(self) -> float:
        """Legged bases: trotting gait frequency [Hz], in (0, 100]."""
    @gait_hz.setter
    def gait_hz(self, value: float) -> None: ...
    @property
    def gait_bob_m(self) -> float:
        """Legged bases: amplitude of a walking body's bob (height) [m], in [0, 1]."""
    @gait_bob_m.setter
    def gait_bob_m(self, value: float) -> None: ...
    @property
    def gait_sway_rad(self) -> float:
        """Legged bases: amplitude of a walking body's sway (roll) [rad], in [0, 0.5]."""
    @gait_sway_rad.setter
    def gait_sway_rad(self, value: float) -> None: ...
    @property
    def settle_s(self) -> float:
        """Time kept running after the last waypoint [s]."""
    @settle_s.setter
    def settle_s(self, value: float) -> None: ...
    @property
    def torn_residual_energy(self) -> float:
        """A sample whose chain E exceeds this [m^2] is torn (default 1e-5)."""
    @torn_residual_energy.setter
    def torn_residual_energy(self, value: float) -> None: ...
    @property
    def control(self) -> ControlOptions:
        """ControlOptions of the plan (a reference: options.control.method = 'bfgs' works)."""
    @control.setter
    def control(self, value: ControlOptions) -> None: ...

# ------------------------------------------------------------------ viewer ----

def viewer_available() -> bool:
    """Whether this build carries the viewer's JavaScript (else view_html raises RuntimeError)."""

def view_html(
    model: Model,
    trajectory: Optional[str] = None,
    replay: Optional[str] = None,
    workspace: Optional[str] = None,
    meshes: bool = False,
    color_by: str = "body",
    mesh_root: Optional[str | os.PathLike[str] | Sequence[str | os.PathLike[str]]] = None,
    controls: Optional[ArrayLike] = None,
    deflection: Optional[float] = None,
    wrench: Optional[ArrayLike] = None,
    dynamics: Optional[str] = None,
) -> Tuple[str, ViewResult]:
    """(html, info): the self-contained page of `ccma view` and its summary (a ViewResult: the command's JSON without out), animated along a trajectory CSV or a replay
    directory, or with a `ccma workspace` CSV drawn as a point cloud (at most one of the three);
    meshes=True draws the bodies' STL meshes (`ccma view --meshes`; files relative to the folder of
    the model's file), read only from inside that folder (symlinks resolved) and the folders of
    mesh_root, a folder or a list (`--mesh_root`); the page never holds an absolute path."""
