"""The results of ccma's analyses in Python: one class per `ccma` command.

Attributes are the keys of the command's JSON (docs/cli.md), with its meaning
and unit; `to_dict()` is that JSON document (python/ccma/_records.py). The
names follow one rule: a Python name is the tool's name, a flag that is a
Python keyword taking a trailing underscore (`--lambda` is `lambda_`, `--from`
is `from_`). Results of commands that write a CSV carry it as a ccma.Table
(`table`, `to_columns()`, `to_records()`, `to_dataframe()`, `to_csv(path)`).

ForwardResult (`ccma simulate`) and ControlResult (`ccma control`) are defined by
the extension (ccma._ccma) and follow the same rules.
"""
from ._records import Field, Record, Result, view  # noqa: F401
from ._tables import Table  # noqa: F401

_POSE = "{position [m], rotation (3x3, from home), rpy [rad]}: the end-effector at the final controls"
_CLEARANCE = ("Record {min [m], pair [a, b], margin [m], below_margin}: the smallest clearance at the final "
              "configuration (min_on_path, pair_on_path over the steps); None without collision geometry")


class _Tabled(Result):
    @property
    def table(self):
        """The command's CSV as a ccma.Table (its header names, its rows)."""
        return self._table(None)


class TrajectoryResult(_Tabled):
    """`ccma trajectory` (ControlProblem.follow): the JSON summary as attributes, the
    CSV (one row per path step) as `table`."""

    _main_table = "trajectory"
    _elsewhere = {
        "time": "per-step values are the table's columns: result.table['time_s']",
        "targets": "result.table's target_x_m ... target_yaw_rad columns",
        "reached": "result.table['reached'] is the step's flag; the reached pose is x_m ... yaw_rad",
        "residual_energy": "result.table['residual_energy_m2']",
        "error": "result.table['error_m_or_rad']",
        "step_reached": "result.table['reached']",
    }
    model = Field("model", "the model's name")
    method = Field("method", "the control method: 'lm' or 'bfgs'")
    converged = Field("converged", "every waypoint reached (bool)")
    waypoints = Field("waypoints", "how many waypoints were given")
    steps = Field("steps", "path steps taken (the table's rows)")
    iterations = Field("iterations", "outer iterations of all steps")
    max_residual_energy = Field("max_residual_energy", "largest E over the steps [m^2]")
    max_error = Field("max_error", "largest final error over the waypoints [m or rad]")
    conditioning = Field("conditioning", "Record {min_singular_value_dX_du_on_path [m or rad per control unit], "
                                         "min_dG_ds_pivot_ratio_on_path [1]}; None without steps")
    secondary = Field("secondary", "Record of the null-space objective's weights and steps; None when off")
    solve_time_ms = Field("solve_time_ms", "wall time [ms]")
    out = Field("out", "the CSV file written (follow(..., out=PATH)); None when none was written")
    controls = Field("controls", "the controls at the end (3 per base: x [m], y [m], theta [rad]; then actuated "
                                 "joints [rad or m])")
    end_effector = Field("end_effector", _POSE)
    clearance = Field("clearance", _CLEARANCE)
    compensation = Field("compensation", "follow(..., compensate=True): Record {rounds (rigid control solves, all "
                                         "steps), max_miss [m or rad]}; None otherwise")
    warning = Field("warning", "the first waypoint not reached ('' when every one was)", "")


class PlanResult(_Tabled):
    """`ccma plan` (ccma.plan): the JSON summary as attributes, the CSV (the columns of
    `ccma trajectory`'s) as `table`."""

    _main_table = "plan"
    _elsewhere = dict(TrajectoryResult._elsewhere, **{
        "note": "why the greedy trajectory was kept is in result.warning",
        "controls": "result.controls are the final controls; per step: the table's u... columns",
        "clearance": "result.clearance is the final Record; per step: result.table['clearance_m']",
    })
    model = Field("model", "the model's name")
    converged = Field("converged", "every waypoint reached (bool)")
    used = Field("used", "'plan' (the optimised trajectory) or 'greedy' (kept: see warning)")
    waypoints = Field("waypoints", "how many waypoints were given")
    steps = Field("steps", "path steps (the table's rows)")
    iterations = Field("iterations", "Gauss-Newton iterations of the whole path")
    stopped_by = Field("stopped_by", "why the optimisation stopped: 'converged', 'plan_iterations' or 'plan_time_s'")
    finishing = Field("finishing", "Record {repaired_rows, inserted_rows}: rows brought back to the margin, "
                                   "midpoint rows added")
    shortfall = Field("shortfall", "only when the finished plan stayed below the margin: Record {step, midpoint, "
                                   "time_s [s], torn, then residual_energy [m^2] or pair, clearance_m [m], "
                                   "floor_m [m], shortfall_m [m]}; None otherwise", None)
    greedy = Field("greedy", "Record {reached_waypoints, travel_m [m], min_clearance_m [m] (with collision "
                             "geometry)}: the greedy trajectory's measures")
    plan = Field("plan", "Record, the same measures of the optimised trajectory")
    solve_time_ms = Field("solve_time_ms", "wall time [ms]")
    out = Field("out", "the CSV file written (plan(..., out=PATH)); None when none was written")
    controls = Field("controls", "the controls at the end (3 per base, then actuated joints)")
    end_effector = Field("end_effector", _POSE)
    clearance = Field("clearance", _CLEARANCE)
    warning = Field("warning", "why the greedy trajectory was kept, or that not every waypoint was reached ('' "
                               "when neither)", "")


class StaticsResult(Result):
    """`ccma statics` (ccma.statics): static equilibrium at the problem's configuration."""

    model = Field("model", "the model's name")
    assembled = Field("assembled", "E below the assembly tolerance at that configuration (bool)")
    residual_energy = Field("residual_energy", "E [m^2]")
    controls = Field("controls", "the controls (3 per base, then actuated joints)")
    end_effector = Field("end_effector", _POSE)
    bodies = Field("bodies", "list of Record {name, position [m], rpy [rad], quaternion [w, x, y, z]}")
    joints = Field("joints", "list of Record {name, point [m], force [N], moment [N*m]}: what between[0] exerts "
                             "on between[1], world frame, moment about point")
    actuators = Field("actuators", "list of Record {name, kind ('base_x', 'base_y', 'base_theta', 'joint'), "
                                   "effort [N or N*m]}, in control order")
    determinate = Field("determinate", "the loads fix the reactions (else minimum-norm ones)")
    balanced = Field("balanced", "the joints can hold the loads")
    unbalanced_load = Field("unbalanced_load", "what they cannot hold [N or N*m]")
    within_limits = Field("within_limits", "every effort within its limit; None without limits")
    limiting = Field("limiting", "names beyond their limits; None without limits")
    ee_covariance = Field("ee_covariance", "6x6 end-effector covariance from the bases' pose noise [m^2, m*rad, "
                                           "rad^2]; None where dG/ds is singular")
    noise = Field("noise", "Record {mocap_noise_m [m], mocap_noise_rad [rad]}")
    payload_capacity = Field("payload_capacity", "Record {mass [kg], limiting, note?}; None without limits")
    clearance = Field("clearance", "Record {min [m], pair, margin [m], below_margin}; None without collision "
                                   "geometry")
    compliant_reactions = Field("compliant_reactions", "True when the model has stiffness keys: joints, actuators "
                                                       "and determinate are the compliant mechanism's; None "
                                                       "otherwise")
    deflection = Field("deflection", "Record {end_effector [dx, dy, dz [m], rx, ry, rz [rad]], max_body_m [m], "
                                     "held}: the linear yield under the loads, controls held; None without "
                                     "stiffness")
    ee_compliance = Field("ee_compliance", "6x6 end-effector compliance [m/N, m/(N*m), rad/(N*m)], symmetric "
                                           "positive semi-definite; None without stiffness")
    ee_stiffness = Field("ee_stiffness", "6x6 inverse of ee_compliance [N/m, N, N*m/rad]; None when it is "
                                         "singular (ee_stiffness_note says why) or without stiffness")
    ee_stiffness_note = Field("ee_stiffness_note", "why ee_stiffness is None; None when it is given")
    controlled_stiffness = Field("controlled_stiffness", "the inverse of ee_compliance's block over the model's "
                                                         "controlled components (their order); None when that "
                                                         "block is singular or the mechanism is not held "
                                                         "(controlled_stiffness_note says why) or without stiffness")
    controlled_stiffness_note = Field("controlled_stiffness_note", "why controlled_stiffness is None; None when "
                                                                   "it is given")
    most_compliant = Field("most_compliant", "Record {direction (unit), compliance [m/N]}: the largest eigenvalue "
                                             "of ee_compliance's translational block; None without stiffness")
    warning = Field("warning", "what makes the reactions doubtful ('' when nothing)", "")


class CheckResult(Result):
    """`ccma check` (ccma.check): the model's counts and its mobility at home."""

    model = Field("model", "the model's name")
    bodies = Field("bodies", "number of bodies")
    mobile_bases = Field("mobile_bases", "number of mobile bases")
    joints = Field("joints", "number of joints")
    state_size = Field("state_size", "6 per body")
    controls = Field("controls", "number of controls")
    effective_controls = Field("effective_controls", "controls the solver changes")
    constraints = Field("constraints", "rows of C")
    rigid_with_controls_fixed = Field("rigid_with_controls_fixed", "no free motion with the controls held")
    end_effector_dof = Field("end_effector_dof", "end-effector motions the controls make at home")
    end_effector_dof_nonholonomic = Field("end_effector_dof_nonholonomic",
                                          "the same when differential bases cannot move sideways")
    assembled_at_home = Field("assembled_at_home", "E at home below the assembly tolerance")
    constraint_rank = Field("constraint_rank", "rank of dC/ds")
    dof_with_controls_fixed = Field("dof_with_controls_fixed", "free motions with the controls held")
    dof_with_controls_free = Field("dof_with_controls_free", "motions with the controls free")
    smallest_singular_value = Field("smallest_singular_value", "of dC/ds")
    energy_at_home = Field("energy_at_home", "E at home [m^2]")
    independent_controls = Field("independent_controls",
                                 "control directions the mechanism can follow at home (fewer than "
                                 "effective_controls: most control vectors cannot be assembled)")
    controlled = Field("controlled", "the controlled components, among x y z roll pitch yaw")
    free_motions = Field("free_motions", "list of Record {bodies: names}: a basis of the free motions")
    warnings = Field("warnings", "what a user would not expect of the mechanism; None when nothing")
    warning = Field("warning", "the warnings joined with '; '; None when nothing")
    note = Field("note", "over-actuated by design: how many controls are independent; None otherwise")
    clearance = Field("clearance", "Record, the clearance at home; None without collision geometry")


class WorkspaceResult(_Tabled):
    """`ccma workspace` (ccma.workspace): the JSON summary as attributes, the map (the
    CSV, one row per sample) as `table`. Unreachable rows hold NaN controls (the CSV
    leaves them empty) and sigma_min = ee_std_m = 0, as the CSV. `details` is a second
    table, Python's only: per sample converged, assembled, steps, tile, warning."""

    _main_table = "workspace"
    _elsewhere = {
        "poses": "the sampled components are the table's columns x, y, z, roll, pitch, yaw (the controlled ones)",
        "controls": "the table's u0, u1, ... columns (NaN when unreachable)",
        "reachable": "result.reachable counts the reachable samples; per sample: result.table['reachable']",
        "converged": "result.details['converged']",
        "assembled": "result.details['assembled']",
        "steps": "result.details['steps']",
        "tile": "result.details['tile']",
        "warning": "result.details['warning']",
        "residual_energy": "result.table['residual_energy']",
        "error": "result.table['error']",
        "sigma_min": "result.table['sigma_min']",
        "rcond": "result.table['rcond']",
        "max_limit_violation": "result.table['max_limit_violation']",
        "limited_by": "result.table['limited_by']",
        "wave": "result.table['wave']",
        "start": "result.table['start']",
    }
    model = Field("model", "the model's name")
    out = Field("out", "the CSV file written (out=PATH); None when none was written")
    samples = Field("samples", "how many samples (the table's rows)")
    reachable = Field("reachable", "how many samples are reachable")
    seconds = Field("seconds", "wall time [s]")
    threads = Field("threads", "local worker threads")
    tiles = Field("tiles", "tiles of the map")
    tile_size = Field("tile_size", "a tile's side [cells per range]")
    mode = Field("mode", "'grid' or 'random'")
    components = Field("components", "the sampled components, in range order")
    tiles_from_store = Field("tiles_from_store", "tiles read back from the store; None without a store")

    @property
    def details(self):
        """ccma.Table, one row per sample: converged, assembled, steps, tile, warning (Python's only)."""
        return self._tables["details"]


class DesignResult(Result):
    """`ccma design` (ccma.design): attributes as the command's JSON; `new_model` is
    the designed ccma.Model (what `out` holds)."""

    _elsewhere = {
        "parameters": "result.changed[k].parameter",
        "old": "result.changed[k].old",
        "new": "result.changed[k].new",
        "targets_before": "result.reached_before (per target: reached)",
        "message": "result.warning",
        "model": "result.model is the model's name; the designed Model is result.new_model",
    }
    model = Field("model", "the model's name")
    out = Field("out", "the model file written (out=PATH); None when none was written")
    converged = Field("converged", "every target reached with margin in the designed model")
    reached = Field("reached", "per target: reached in the designed model (bool array)")
    reached_before = Field("reached_before", "per target: reached in the given model (bool array)")
    targets = Field("targets", "list of Record {reached, error [m or rad] (-1: not solved), min_singular_value, "
                               "within_limits}, in the designed model")
    iterations = Field("iterations", "design iterations")
    changed = Field("changed", "list of Record {parameter, old [m], new [m], unit}")
    changed_points = Field("changed_points", "list of Record {joint, old_point [m], new_point [m]}")
    objective = Field("objective", "Record {name, unit, maximised, before, after, iterations, stopped}; None for "
                                   "objective='reach'")
    warning = Field("warning", "why it did not converge ('' when it did)", "")

    @property
    def new_model(self):
        """The designed ccma.Model (as written to `out`)."""
        return self._new_model


class ImportResult(Result):
    """`ccma import` (ccma.import_robot): the summary as attributes; `new_model` is the
    imported ccma.Model (what `out` holds)."""

    out = Field("out", "the model file written (out=PATH); None when none was written")
    bodies = Field("bodies", "number of bodies")
    joints = Field("joints", "number of joints")
    closures = Field("closures", "number of loop closures")
    actuated = Field("actuated", "the actuated joints' names")
    controlled = Field("controlled", "the model's controlled components, in x y z roll pitch yaw order")
    controlled_chosen = Field("controlled_chosen", "True when import chose them (none given or stored): "
                              "the components the motors move at home, translations first")
    assembled = Field("assembled", "assembled at home (always True: import refuses otherwise)")
    residual_energy = Field("residual_energy", "E at home [m^2]")
    controls = Field("controls", "the home controls")
    closure_gaps = Field("closure_gaps", "list of Record {name, gap_m [m], gap_rad [rad]}: how far apart each "
                                         "closure's frames are in the source")
    motor_moves = Field("motor_moves", "list of Record {name, move [rad or m]}: how far assembling at home moved "
                                       "each motor from its source position")
    collision_capsules = Field("collision_capsules", "with collision_radius: capsules written to collision.links; "
                               "None without")
    collision_ignored_pairs = Field("collision_ignored_pairs", "with collision_radius: body pairs closer than "
                                    "the margin at home, written to collision.ignore; None without")

    @property
    def new_model(self):
        """The imported ccma.Model, assembled at home."""
        return self._new_model


class ExportResult(Result):
    """`ccma export` (ccma.export): what was written."""

    out = Field("out", "the URDF, SDFormat or MJCF file written")
    format = Field("format", "'urdf', 'sdf' or 'mjcf'")
    closures = Field("closures", "the closure file written beside the URDF; None for sdf and mjcf")
    links = Field("links", "links written (urdf, sdf)")
    joints = Field("joints", "joints written")
    loops = Field("loops", "loop-closing joints")
    bodies = Field("bodies", "bodies written (mjcf)")
    equalities = Field("equalities", "connect and weld constraints written (mjcf)")
    actuators = Field("actuators", "position actuators written, one per control (mjcf)")


class GenerateResult(Result):
    """`ccma generate` (ccma.generate): the generated model's counts as attributes;
    `new_model` is the generated ccma.Model and `text` its model file."""

    out = Field("out", "the model file written; None when out= was not given")
    model = Field("model", "the model's name")
    agents = Field("agents", "mobile bases (0 for stewart_gough)")
    actuated_joints = Field("actuated_joints", "actuated joints")
    bodies = Field("bodies", "bodies")
    state_size = Field("state_size", "6 per body and base")
    controls = Field("controls", "controls")

    @property
    def new_model(self):
        """The generated ccma.Model."""
        return self._new_model

    @property
    def text(self):
        """The model file (YAML text), as `ccma generate` writes it."""
        return self._text


class ViewResult(Result):
    """`ccma view` (ccma.view with out=, ccma.view_html): the page's summary."""

    out = Field("out", "the HTML file written; None from view_html")
    bytes = Field("bytes", "size of the page [bytes]")
    frames = Field("frames", "animation frames")
    source = Field("source", "'model', 'controls', 'trajectory', 'replay' or 'workspace'")
    flagged_frames = Field("flagged_frames", "frames marked red")
    not_assembled_frames = Field("not_assembled_frames", "frames not assembled")
    branch_jumps = Field("branch_jumps", "branch jumps while re-assembling")
    beyond_work_bound_frames = Field("beyond_work_bound_frames", "frames not attempted; None when none")
    clearance_below_margin_frames = Field("clearance_below_margin_frames",
                                          "frames below the margin; None without collision geometry")
    mesh_files = Field("mesh_files", "mesh files read; None without meshes")
    mesh_bytes = Field("mesh_bytes", "bytes of mesh read; None without meshes")
    max_load = Field("max_load", "largest joint reaction [N] (color_by='load'); else None")
    unbalanced_frames = Field("unbalanced_frames", "color_by='load': frames not balanced; else None")
    indeterminate_frames = Field("indeterminate_frames", "color_by='load': frames indeterminate; else None")
    deflection_scale = Field("deflection_scale", "deflection=SCALE: the loaded shape's exaggeration; else None")
    max_deflection_m = Field("max_deflection_m", "deflection=: the largest body deflection [m]; else None")
    deflection_converged = Field("deflection_converged", "deflection=: the loaded equilibrium was found; else None")
    load_fraction = Field("load_fraction", "deflection=: the fraction of the loads the shape holds; else None")
    max_effort_share = Field("max_effort_share", "dynamics=: the largest effort share of a limit; else None")
    effort_frames_beyond_limit = Field("effort_frames_beyond_limit",
                                       "dynamics=: frames with an actuator beyond its limit; else None")
    workspace_points = Field("workspace_points", "points of a workspace map; else None")
    workspace_reachable = Field("workspace_reachable", "reachable points of a workspace map; else None")


class DynamicsResult(_Tabled):
    """`ccma dynamics` (ccma.dynamics): inverse dynamics along a trajectory; the JSON
    summary as attributes, the --out CSV (one row per trajectory row: time_s, an
    effort column per control [N or N*m], kinetic_J, potential_J, power_W) as `table`."""

    _main_table = "dynamics"
    _elsewhere = {
        "efforts": "per-row efforts are the table's columns: result.table['u_<joint>_Nm'] ...",
        "power_W": "result.table['power_W']",
    }
    rows = Field("rows", "rows of the trajectory")
    duration_s = Field("duration_s", "[s] the last row's time minus the first's")
    assembled = Field("assembled", "every row assembled (bool)")
    not_assembled_rows = Field("not_assembled_rows", "rows that did not (empty cells in the table)")
    actuators = Field("actuators", "list of Record {name, kind, peak_effort [N or N*m], peak_time_s [s], rms_effort, "
                                   "limit ([lo, hi] or None), peak_rate [m/s or rad/s], rate_limit (velocity_limit "
                                   "or None), within_limits (effort and rate)}, in control order")
    within_limits = Field("within_limits", "every actuator within its limits at every assembled row")
    limiting = Field("limiting", "names of the actuators beyond a limit somewhere")
    energy_J = Field("energy_J", "[J] the net work of all controls (trapezoid of power_W)")
    max_power_W = Field("max_power_W", "[W] the largest power_W")
    max_rate_inconsistency = Field("max_rate_inconsistency", "largest |J_s q' + J_u u'| over the rows")
    out = Field("out", "the CSV file written (dynamics(..., out=PATH)); None when none was written")
    warning = Field("warning", "rows not assembled, a limit exceeded or inconsistent rates ('' when none)", "")


class RetimeResult(_Tabled):
    """`ccma retime` (ccma.retime): the fastest rest-to-rest timing of a trajectory's
    path within every limit; the JSON summary as attributes, the retimed CSV (the
    input with new time_s cells) as `table` and `csv_text` (None when infeasible)."""

    _main_table = "trajectory"
    feasible = Field("feasible", "a timing within every limit was found (bool)")
    rows = Field("rows", "rows of the trajectory")
    original_duration_s = Field("original_duration_s", "[s] the input's last time minus its first")
    duration_s = Field("duration_s", "[s] the retimed path's; None when infeasible")
    uniform_duration_s = Field("uniform_duration_s", "[s] the best uniform time scaling's; None when infeasible "
                                                     "or unbounded")
    method = Field("method", "'topp-ra' or 'uniform': which verified timing was faster; None when infeasible")
    verified_scale = Field("verified_scale", "the factor the verification stretched TOPP-RA's timing by (1: none)")
    limiting = Field("limiting", "list of Record {name, kind ('effort', 'push', 'velocity'), share}: the limits "
                                 "that set the speed, largest share first")
    infeasible = Field("infeasible", "when infeasible: Record {row, line, time_s, kind, control, effort, limit}, "
                                     "the first row beyond a limit at rest; None otherwise")
    out = Field("out", "the CSV file written (retime(..., out=PATH), when feasible); None otherwise")
    warning = Field("warning", "why it is infeasible ('' when feasible)", "")

    @property
    def csv_text(self):
        """The retimed CSV's text: the input, every byte as it was but the time_s cells; None when infeasible."""
        return self._csv_text


class ReplayResult(_Tabled):
    """`ccma replay` (ccma.replay): the summary as attributes, the two CSV files as
    tables: `tables['end_effector']` (time_s, cmd_*, the tracked pose, err_* [mm or
    rad], residual_energy_m2, torn) and `tables['bases']` (time_s, set*/base* poses,
    actuated joints, torn)."""

    _main_table = "end_effector"
    model = Field("model", "the model's name")
    simulation = Field("simulation", "always True: a simulation, not hardware")
    converged = Field("converged", "the control solution reached every waypoint")
    torn = Field("torn", "the chain could not follow the bases in some sample")
    torn_samples = Field("torn_samples", "how many samples were torn")
    first_torn_time_s = Field("first_torn_time_s", "[s]; None if never torn")
    max_residual_energy = Field("max_residual_energy", "largest E of the chain [m^2]")
    torn_residual_energy = Field("torn_residual_energy", "E above which a sample is torn [m^2]")
    failed_step_time_s = Field("failed_step_time_s", "[s] where the plan stopped; None if it reached every waypoint")
    trustworthy = Field("trustworthy", "converged and never torn: only then does rmse measure tracking")
    duration_s = Field("duration_s", "[s]")
    samples = Field("samples", "output samples (the tables' rows)")
    noise = Field("noise", "Record: the simulated imperfections")
    controller = Field("controller", "Record: the bases' PI controller")
    rmse = Field("rmse", "Record: tracked vs commanded per reported component, x_mm ... [mm], yaw_rad ... [rad]")
    paper_hardware_rmse = Field("paper_hardware_rmse", "the paper's hardware rows (its models only); else None")
    warning = Field("warning", "why the result is not trustworthy ('' when it is)", "")


class DesignSweepResult(_Tabled):
    """ccma.design_sweep (Python's only): one table row per candidate design, in grid
    order: one column per parameter [m], then all_reached, min_singular_value (0 when a
    target is unreachable) and feasible; `reached` is (candidates x targets) bool."""

    _main_table = "candidates"

    def __init__(self, parameters, table, reached):
        super().__init__({}, {"candidates": table})
        self._parameters = list(parameters)
        self._reached = reached

    @property
    def parameters(self):
        """The parameters' names, as given."""
        return list(self._parameters)

    @property
    def reached(self):
        """(candidates x targets) bool: which targets each candidate reaches."""
        return self._reached

    def __len__(self):
        return len(self.table)

    def __eq__(self, other):
        if not isinstance(other, DesignSweepResult):
            return NotImplemented
        return self._parameters == other._parameters and self.table == other.table and \
            self._reached.tolist() == other._reached.tolist()

    __hash__ = None

    def __getitem__(self, index):
        import warnings
        warnings.warn("DesignSweepResult[i] is deprecated: use result.table (or result.to_records()) and "
                      "result.reached", DeprecationWarning, stacklevel=2)
        table = self.table
        return {"values": {n: float(table[n][index]) for n in self._parameters},
                "reached": [bool(r) for r in self._reached[index]],
                "all_reached": bool(table["all_reached"][index]),
                "min_singular_value": float(table["min_singular_value"][index]),
                "feasible": bool(table["feasible"][index])}

    def __repr__(self):
        return "<ccma.DesignSweepResult %d candidates, %d feasible>" % (len(self), int(self.table["feasible"].sum()))
