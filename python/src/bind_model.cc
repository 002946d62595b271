// Models: ccma.load_model(path) -> Model (read-only), ccma.ModelError.
#include <filesystem>
#include <optional>

#include <pybind11/eigen.h>
#include <pybind11/stl/filesystem.h>
#include <pybind11/stl.h>

#include "ccma/model.h"
#include "formats/model_loader.h"
#include "formats/obstacles_file.h"
#include "python/src/bindings.h"

namespace py = pybind11;

namespace ccma::python {
namespace {

const char* ActuationName(Actuation a) { return a == Actuation::kComplete ? "complete" : "reduced"; }

// The controlled components' names ("x", "y", "z", "roll", "pitch", "yaw").
std::vector<std::string> Controlled(const EndEffector& ee) {
  std::vector<std::string> names;
  for (int i = 0; i < 6; ++i) {
    if (ee.controlled[i]) names.emplace_back(kEndEffectorComponentNames[i]);
  }
  return names;
}

// The loader's warnings (unknown keys, implausible magnitudes) as
// UserWarnings; a warning turned into an error (-W error)
// propagates as that error.
void Warn(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) < 0) throw py::error_already_set();
  }
}

void BindParts(py::module_& m) {
  py::class_<Body>(m, "Body", "A rigid body (mobile bases are bodies too).")
      .def_readonly("name", &Body::name)
      .def_readonly("R_WB_home", &Body::R_WB_home, "home orientation, 3x3 rotation (world from body)")
      .def_readonly("p_WB_home", &Body::p_WB_home, "home position of the body frame [m]")
      .def_readonly("base_index", &Body::base_index, "index into Model.mobile_bases, or -1")
      .def_property_readonly("is_mobile_base", &Body::is_mobile_base)
      .def("__repr__", [](const Body& b) { return "<ccma.Body '" + b.name + "'>"; });
  py::class_<MobileBase>(m, "MobileBase",
                         "A mobile base: controls x [m], y [m], theta [rad]; a legged base also height [m], "
                         "roll [rad], pitch [rad].")
      .def_readonly("name", &MobileBase::name)
      .def_readonly("body", &MobileBase::body, "index into Model.bodies")
      .def_property_readonly("type", [](const MobileBase& b) { return KindOf(b).name(); },
                             "'omni', 'differential' or 'legged'")
      .def_property_readonly(
          "control_names",
          [](const MobileBase& b) {
            std::vector<std::string> names;
            for (const BaseControl& c : KindOf(b).controls()) names.push_back(std::string(c.name) + "_" + c.unit);
            return names;
          },
          "its controls in the order of u, with units ('x_m', 'y_m', 'theta_rad', ...)")
      .def_property_readonly("body_height", [](const MobileBase& b) { return b.legged.height; },
                             "a legged base's home body height [m] (0 for wheeled bases)")
      .def_property_readonly("actuation", [](const MobileBase& b) { return ActuationName(b.actuation); },
                             "'complete' or 'reduced' (reduced: its heading is no control)")
      .def_readonly("home_pose", &MobileBase::home_pose, "x [m], y [m], theta [rad] at home")
      .def("__repr__", [](const MobileBase& b) {
        return "<ccma.MobileBase '" + b.name + "' " + KindOf(b).name() + ">";
      });
  py::class_<Joint>(m, "Joint", "A joint of the passive chain between bodies A and B (-1 = world).")
      .def_readonly("name", &Joint::name)
      .def_property_readonly("type", [](const Joint& j) { return JointTypeName(j.type); },
                             "'revolute', 'spherical', 'universal', 'prismatic' or 'fixed'")
      .def_readonly("body_a", &Joint::body_a)
      .def_readonly("body_b", &Joint::body_b)
      .def_readonly("p_A", &Joint::p_A, "joint point in A's frame [m]")
      .def_readonly("p_B", &Joint::p_B, "joint point in B's frame [m]")
      .def_readonly("a_A", &Joint::a_A, "axis in A's frame (revolute, prismatic, universal's first)")
      .def_readonly("a_B", &Joint::a_B, "the same axis in B's frame (revolute, prismatic)")
      .def_readonly("b_B", &Joint::b_B, "universal: the second axis, in B's frame")
      .def_readonly("actuated", &Joint::actuated, "its coordinate is a control")
      .def_readonly("control", &Joint::control, "index into the controls when actuated, else -1")
      .def_readonly("limited", &Joint::limited)
      .def_readonly("lower", &Joint::lower, "lower limit [rad or m] when limited")
      .def_readonly("upper", &Joint::upper, "upper limit [rad or m] when limited")
      .def_readonly("q_home", &Joint::q_home, "the coordinate's value at home [rad or m]")
      .def_readonly("line", &Joint::line, "line in the model file")
      .def_property_readonly("has_coordinate", &Joint::has_coordinate)
      .def("__repr__", [](const Joint& j) {
        return "<ccma.Joint '" + j.name + "' " + JointTypeName(j.type) + ">";
      });
  py::class_<EndEffector>(m, "EndEffectorSpec", "Where the end-effector is and what is controlled.")
      .def_readonly("body", &EndEffector::body, "index into Model.bodies")
      .def_readonly("p_B", &EndEffector::p_B, "the point in the body's frame [m]")
      .def_readonly("p_W_home", &EndEffector::p_W_home, "the point in world at home [m]")
      .def_property_readonly("controlled", &Controlled, "controlled components, e.g. ['x', 'y', 'z', 'yaw']");
}

void BindModelClass(py::module_& m) {
  py::class_<Model>(m, "Model",
                    "A loaded mechanism: constant, shared by every problem built on it "
                    "(ccma.load_model). Controls: 3 per mobile base (x [m], y [m], theta [rad]; 6 per legged base: also height [m], roll, pitch [rad]), "
                    "then one per actuated joint [rad or m].")
      .def_readonly("name", &Model::name)
      .def_readonly("description", &Model::description)
      .def_readonly("source", &Model::source, "the file it was loaded from")
      .def_readonly("bodies", &Model::bodies)
      .def_readonly("mobile_bases", &Model::mobile_bases)
      .def_readonly("joints", &Model::joints)
      .def_readonly("end_effector", &Model::end_effector)
      .def_property_readonly("num_bodies", &Model::num_bodies)
      .def_property_readonly("num_bases", &Model::num_bases)
      .def_property_readonly("num_controls", &Model::num_controls)
      .def("base_control", &Model::base_control, py::arg("k"), "index into the controls of base k's x")
      .def_property_readonly("num_constraints", &Model::num_constraints, "rows of C")
      .def_property_readonly("state_size", &Model::state_size, "6 per body (tangent size)")
      .def_property_readonly("home_controls", &Model::home_controls, "controls at home (NumPy vector)")
      .def_property_readonly("effective_control_indices", &Model::effective_control_indices,
                             "indices of the controls the control solver may change")
      .def_property_readonly("controlled", [](const Model& model) { return Controlled(model.end_effector); })
      .def("find_body", &Model::FindBody, py::arg("name"), "index of the body, or -1")
      .def("find_joint", &Model::FindJoint, py::arg("name"), "index of the joint, or -1")
      .def("__repr__", [](const Model& model) {
        return "<ccma.Model '" + model.name + "': " + std::to_string(model.num_bodies()) + " bodies, " +
               std::to_string(model.num_bases()) + " bases, " + std::to_string(model.joints.size()) +
               " joints>";
      });
}

}  // namespace

void BindModel(py::module_& m) {
  py::register_exception<ModelError>(m, "ModelError", PyExc_ValueError).attr("__doc__") =
      "Raised when a model file (or model text) cannot be read or is not a valid model "
      "(docs/model_format.md): by load_model, load_model_from_string, and by view, workspace "
      "and design_sweep given a model file's path. Carries one argument, the message "
      "'file:line: key: what' (str(e), e.args[0]), the same text `ccma check` prints. "
      "A subclass of ValueError.";
  BindParts(m);
  BindModelClass(m);
  m.def(
      "load_model",
      [](const std::filesystem::path& path, const std::optional<std::filesystem::path>& obstacles) {
        std::vector<std::string> warnings;
        Model model = LoadModel(path.string(), &warnings);
        if (obstacles) AddObstaclesFromFile(obstacles->string(), &model, &warnings);
        Warn(warnings);
        return model;
      },
      py::arg("path"), py::arg("obstacles") = py::none(),
      "Reads and validates a model file (YAML or JSON, docs/model_format.md). Raises "
      "ccma.ModelError with 'file:line: key: what' on any problem (a misspelt key too); other "
      "unknown keys, lengths above 100 m and angles above 2 pi give a UserWarning. obstacles: "
      "a file with one key, obstacles: (docs/obstacles.md), added to the model's (`--obstacles`).");
  m.def(
      "load_model_from_string",
      [](const std::string& text, const std::string& source_name) {
        std::vector<std::string> warnings;
        Model model = LoadModelFromString(text, source_name, &warnings);
        Warn(warnings);
        return model;
      },
      py::arg("text"), py::arg("source_name") = "<string>",
      "The same as load_model for model text in memory; source_name stands in for the file name "
      "in messages.");
}

}  // namespace ccma::python
