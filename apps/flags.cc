#include "apps/flags.h"

DEFINE_string(model, "", "model file, YAML or JSON (docs/model_format.md) [path]");
DEFINE_string(obstacles, "",
              "obstacles file, added to the model's: a YAML mapping with the one key obstacles: "
              "(docs/model_format.md, Collision geometry and obstacles) [path]");
DEFINE_string(controls, "",
              "comma-separated controls, per mobile base in file order: x [m], y [m], theta [rad] (a legged base also height [m], roll, pitch [rad]), then one per actuated joint "
              "(default: the model's home controls)");
DEFINE_string(waypoints, "", "waypoint CSV: time,x,y,z,roll,pitch,yaw (docs/waypoints.md) [path]");
DEFINE_string(out, "", "output file or folder (see the command) [path]");
DEFINE_string(from, "", "input file (see the command) [path]");
DEFINE_string(wrench, "",
              "the loads' external wrench on the end-effector body, world frame: fx,fy,fz [N] at the end-effector "
              "point, mx,my,mz [N*m]; each in [-1e6, 1e6] (default none) [list]");
DEFINE_bool(compensate, false,
            "choose the controls whose loaded end-effector (a model with stiffness keys, under gravity, the payload "
            "and --wrench) reaches the target, or every path step's target (default off) [bool]");
DEFINE_int32(seed, 1, "seed of every random draw [integer >= 0]");
DEFINE_string(method, "lm", "control outer loop: lm (Levenberg-Marquardt) or bfgs (the paper's) [lm|bfgs]");
DEFINE_double(max_step_m, 0.010, "path step: end-effector translation per control step, 1e-6..1000 [m]");
DEFINE_double(max_step_rad, 0.005, "path step: end-effector rotation per control step, 1e-6..10 [rad]");
DEFINE_double(max_minutes, 10,
              "refuse (status 2) a run whose estimated time, measured on its first seconds, exceeds this; give more "
              "to allow a longer run, (0, 10080] [minutes]");
DEFINE_double(lambda, 0.5, "weight of the residual energy in the control objective, 0 < lambda < 1 [1]");
