// `ccma import` of MuJoCo MJCF files (formats/mjcf_reader.h): what ccma
// exports comes back as the same mechanism, every body where MuJoCo puts it
// at the configuration read; what ccma cannot represent is refused with the
// element named, before MuJoCo sees the file.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <Eigen/Geometry>

#include "analyses/robot_import.h"
#include "bundled_models.h"
#include "ccma/end_effector.h"
#include "formats/mjcf_reader.h"
#include "formats/mjcf_writer.h"
#include "formats/model_generator.h"
#include "formats/model_loader.h"
#include "formats/robot_file.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "tool_run.h"

namespace ccma {
namespace mjcf_import_test {

ImportedRobot ImportExport(const Model& model, const std::string& keyframe = "") {
  const std::string path = testing::ScratchPath("mjcf_import", model.name + ".xml");
  std::ofstream(path) << WriteMjcf(model).mjcf;
  return ImportRobot(ReadMjcf(path, MjcfReadOptions{{}, keyframe}), ImportOptions{});
}

std::vector<Model> Models() {
  std::vector<Model> models;
  for (const std::string& name : testing::BundledModels()) models.push_back(LoadModel(testing::ModelPath(name)));
  StewartOptions stewart;
  models.push_back(LoadModelFromString(GenerateStewartGoughModel(stewart), "generated_stewart_gough"));
  return models;
}

// The same end-effector pose at the same controls: home and controls the
// original's controller finds for targets 2 cm away (seeded).
void ExpectSameMechanism(const Model& original, const Model& imported) {
  ASSERT_EQ(imported.num_controls(), original.num_controls());
  std::vector<Eigen::VectorXd> controls = {original.home_controls()};
  std::mt19937 rng(51);
  std::uniform_real_distribution<double> step(-0.02, 0.02);
  const EndEffectorPose home = ComputeEndEffectorPose(original, State::Home(original));
  for (int k = 0; k < 2; ++k) {
    ControlProblem control(original);
    PoseTarget target;
    target.position = home.position + Eigen::Vector3d{step(rng), step(rng), step(rng)};
    target.rpy = home.rpy;
    if (control.MoveTo(target).assembled) controls.push_back(control.controls());
  }
  for (const Eigen::VectorXd& u : controls) {
    ForwardProblem a(original), b(imported);
    ASSERT_TRUE(a.Assemble(u).assembled);
    ASSERT_TRUE(b.Assemble(u).assembled) << u.transpose();
    EXPECT_LT((a.end_effector().position - b.end_effector().position).norm(), 1e-9) << u.transpose();
    EXPECT_LT((a.end_effector().rotation - b.end_effector().rotation).norm(), 1e-9) << u.transpose();
  }
}

// ccma export --format=mjcf, then import: every body of the model at its
// home pose, the same controls, the same end-effector at the same controls.
TEST(MjcfImport, WhatCcmaExportsComesBackAsTheSameMechanism) {
  for (const Model& model : Models()) {
    SCOPED_TRACE(model.name);
    const ImportedRobot imported = ImportExport(model);
    EXPECT_LT(imported.residual_energy, 1e-20);
    for (int b = 0; b < model.num_bodies(); ++b) {
      const int i = imported.model.FindBody(model.bodies[b].name);
      ASSERT_GE(i, 0) << model.bodies[b].name;
      EXPECT_LT((imported.model.bodies[i].p_WB_home - model.bodies[b].p_WB_home).norm(), 1e-9) << model.bodies[b].name;
    }
    for (const ClosureGap& gap : imported.closure_gaps) EXPECT_LT(gap.gap_m, 1e-9) << gap.name;
    ExpectSameMechanism(model, imported.model);
  }
}

// The masses MuJoCo compiled come along: statics' efforts on the exported
// and imported loaded Stewart platform agree (the exporter's 1 g on the
// massless bodies aside: there are none here).
TEST(MjcfImport, MassesAndGravityComeBack) {
  const Model model = LoadModel(std::string(CCMA_SOURCE_DIR) + "/examples/statics/stewart_gough_loaded.yaml");
  const ImportedRobot imported = ImportExport(model);
  double total = 0, imported_total = 0;
  for (const Body& b : model.bodies) total += b.inertia.mass;
  total += model.end_effector.payload.mass;
  for (const Body& b : imported.model.bodies) imported_total += b.inertia.mass;
  EXPECT_NEAR(imported_total, total, 1e-12);
  EXPECT_LT((imported.model.gravity - model.gravity).norm(), 1e-15);
}

// A keyframe other than qpos0: the bodies sit where MuJoCo puts them there.
TEST(MjcfImport, TheKeyframeNamedIsTheConfigurationRead) {
  const std::string text = R"(<mujoco model="arm">
  <worldbody>
    <body name="link" pos="0 0 1">
      <joint name="shoulder" type="hinge" axis="0 0 1"/>
      <inertial pos="0.25 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>
      <body name="hand" pos="0.5 0 0">
        <joint name="elbow" type="hinge" axis="0 0 1"/>
        <inertial pos="0.1 0 0" mass="0.5" diaginertia="0.001 0.001 0.001"/>
      </body>
    </body>
  </worldbody>
  <actuator><position joint="shoulder"/><position joint="elbow"/></actuator>
  <keyframe><key name="bent" qpos="0.3 -0.5"/></keyframe>
</mujoco>)";
  const RobotDescription robot = ReadMjcfFromString(text, "arm.xml", MjcfReadOptions{{}, "bent"});
  const int hand = robot.FindLink("hand");
  ASSERT_GE(hand, 0);
  // Closed form: the hand's frame at the shoulder (0, 0, 1) + 0.5 (cos 0.3, sin 0.3, 0), turned by 0.3 - 0.5.
  const Eigen::Vector3d p(0.5 * std::cos(0.3), 0.5 * std::sin(0.3), 1);
  EXPECT_LT((robot.links[hand].X_WL.translation() - p).norm(), 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(robot.links[hand].X_WL.linear()).angle(), 0.2, 1e-15);
  EXPECT_EQ(robot.actuated, (std::vector<std::string>{"shoulder", "elbow"}));
  EXPECT_NEAR(robot.joints[robot.FindJoint("elbow")].position, -0.5, 1e-15);
  try {
    ReadMjcfFromString(text, "arm.xml", MjcfReadOptions{{}, "straight"});
    ADD_FAILURE() << "an unknown keyframe was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("arm.xml: no keyframe named 'straight'"), std::string::npos) << e.what();
  }
}

// What ccma cannot represent, or would make MuJoCo open a file: refused
// with the element and its line, before MuJoCo compiles anything.
TEST(MjcfImport, WhatCcmaCannotRepresentIsRefusedNamingTheElement) {
  const std::string head = "<mujoco model=\"m\">\n<worldbody>\n<body name=\"a\">\n<joint name=\"j\" type=\"hinge\"/>\n"
                           "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>\n";
  const std::string tail = "</body>\n</worldbody>\n";
  const struct {
    std::string text, message;
  } cases[] = {
      {"<mujoco model=\"m\">\n<include file=\"other.xml\"/>\n</mujoco>", "m.xml:2: <include> is not supported"},
      {"<mujoco model=\"m\">\n<asset>\n<mesh name=\"x\" file=\"/etc/passwd\"/>\n</asset>\n</mujoco>",
       "m.xml:3: <mesh file=...>: ccma opens no file an MJCF names"},
      {head + tail + "<tendon>\n<fixed name=\"t\"><joint joint=\"j\" coef=\"1\"/></fixed>\n</tendon>\n</mujoco>",
       "m.xml:8: <tendon> is not supported"},
      {head + tail + "<equality>\n<joint joint1=\"j\"/>\n</equality>\n</mujoco>",
       "m.xml:9: <equality><joint> is not supported"},
      {head + "<body name=\"b\"><freejoint name=\"loose\"/><inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>"
              "</body>\n" + tail + "</mujoco>",
       // MuJoCo's compiler refuses it itself, naming the body and its line.
       "m.xml: MuJoCo: Error: free joint can only be used on top level; Object name = b, id = 2, line = 6"},
      {"<robot name=\"r\"/>", "not an MJCF file"},
      {"<mujoco model=\"m\">\n<worldbody>\n<body name=\"a\">\n<joint type=\"screw\"/>\n</body>\n</worldbody>\n</mujoco>",
       "m.xml: MuJoCo:"},
  };
  for (const auto& c : cases) {
    try {
      ReadMjcfFromString(c.text, "m.xml", {});
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const ModelError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
  // A joint whose ref puts it beyond ccma's range (found by fuzzing):
  // refused naming it, not left to the solver's checks.
  try {
    ReadMjcfFromString("<mujoco model=\"m\"><worldbody><body name=\"a\"><joint name=\"far\" type=\"slide\" "
                       "ref=\"35010.8\"/><inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/></body>"
                       "</worldbody></mujoco>", "far.xml", {});
    ADD_FAILURE() << "a position of 35010 m was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("far.xml: joint 'far': its position 35010.8"), std::string::npos) << e.what();
  }
  // Memory the file asks of MuJoCo's data beyond ccma's bound: refused before
  // MuJoCo would allocate it (and end the process when it cannot).
  try {
    ReadMjcfFromString("<mujoco model=\"m\"><size nstack=\"2000000000\"/><worldbody/></mujoco>", "big.xml", {});
    ADD_FAILURE() << "a 15 GB stack was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("big.xml: <size>: MuJoCo's data would take"), std::string::npos) << e.what();
  }
  // Nesting deeper than robot_xml.h allows: refused before any parser.
  std::string deep = "<mujoco model=\"m\"><worldbody>";
  for (int i = 0; i < 200; ++i) deep += "<body>";
  for (int i = 0; i < 200; ++i) deep += "</body>";
  deep += "</worldbody></mujoco>";
  EXPECT_THROW(ReadMjcfFromString(deep, "deep.xml", {}), ModelError);
}

// The command: an .xml whose root is <mujoco> is MJCF; bad input exits 2
// with nothing on stdout and nothing written.
TEST(MjcfImport, TheCommandReadsMjcfAndRefusesBadInput) {
  const Model model = LoadModel(testing::ModelPath("4dof_reduced"));
  const std::string xml = testing::ScratchPath("mjcf_import", "cli.xml");
  std::ofstream(xml) << WriteMjcf(model).mjcf;
  const std::string out = testing::ScratchPath("mjcf_import", "cli.yaml");
  const testing::ToolRun run = testing::RunTool({"import", "--from=" + xml, "--keyframe=home", "--out=" + out});
  ASSERT_EQ(run.status, 0) << run.err;
  const Model back = LoadModel(out);
  EXPECT_EQ(back.num_controls(), model.num_controls());
  const std::string bad = testing::ScratchPath("mjcf_import", "bad.xml");
  std::ofstream(bad) << "<mujoco model=\"m\">\n<include file=\"x.xml\"/>\n</mujoco>\n";
  const std::string bad_out = testing::ScratchPath("mjcf_import", "bad.yaml");
  std::remove(bad_out.c_str());
  const testing::ToolRun refused = testing::RunTool({"import", "--from=" + bad, "--out=" + bad_out});
  EXPECT_EQ(refused.status, 2);
  EXPECT_TRUE(refused.out.empty()) << refused.out;
  EXPECT_NE(refused.err.find("bad.xml:2: <include> is not supported"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::ifstream(bad_out).good());
  const testing::ToolRun keyframe = testing::RunTool({"import", "--from=" + xml, "--keyframe=nope", "--out=" + bad_out});
  EXPECT_EQ(keyframe.status, 2);
  EXPECT_NE(keyframe.err.find("no keyframe named 'nope'"), std::string::npos) << keyframe.err;
}

// Public MJCF files with loops (tests/data/corpus/mjcf/, each folder's
// SOURCE.md and LICENSE): every body where MuJoCo puts it at qpos0, the end-
// effector where a closed form puts it, and the same mechanism after a round
// trip through ccma's own export.
struct PublicFile {
  std::string file;
  std::vector<std::string> actuated;
  std::string ee_link;
  // The end-effector (the link's origin) at controls u, in closed form.
  Eigen::Vector3d (*hand)(const Eigen::VectorXd& u);
  std::vector<Eigen::VectorXd> controls;
};

const std::vector<PublicFile>& PublicFiles() {
  static const std::vector<PublicFile> files = {
      // Genesis' four-bar: a 4 m square in the y-z plane, hinges along x;
      // link_3 (the coupler) translates: its origin at (0, 4 cos q, 4 sin q).
      {"genesis/four_bar_linkage.xml", {"hinge_1"}, "link_3",
       [](const Eigen::VectorXd& u) { return Eigen::Vector3d(0, 4 * std::cos(u[0]), 4 * std::sin(u[0])); },
       {Eigen::VectorXd::Constant(1, 0.0), Eigen::VectorXd::Constant(1, 0.4), Eigen::VectorXd::Constant(1, -0.7)}},
      // MuJoCo's jdotv_connect_2d test: a 0.5 m pendulum from (0, 0, 1) about
      // y, a body pinned at its tip; that body's origin is the pin:
      // (0.5 cos q, 0, 1 - 0.5 sin q). Its own turn (joint3) is the second control.
      {"mujoco/jdotv_connect_2d.xml", {"hinge1", "joint3"}, "lower",
       [](const Eigen::VectorXd& u) { return Eigen::Vector3d(0.5 * std::cos(u[0]), 0, 1 - 0.5 * std::sin(u[0])); },
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.3, 0.2), Eigen::Vector2d(-0.5, 0.4)}},
  };
  return files;
}

TEST(MjcfImport, PublicFilesWithLoopsImportAsMuJoCoPutsThemAndRoundTrip) {
  for (const PublicFile& f : PublicFiles()) {
    SCOPED_TRACE(f.file);
    const std::string path = std::string(CCMA_TEST_DATA_DIR) + "/corpus/mjcf/" + f.file;
    ImportOptions options;
    options.end_effector_link = f.ee_link;
    const ImportedRobot imported = ImportRobot(ReadMjcf(path, MjcfReadOptions{f.actuated, ""}), options);
    EXPECT_EQ(imported.closures, 1);
    // MuJoCo's own bodies at qpos0.
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    ASSERT_NE(m, nullptr) << error;
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    for (int b = 1; b < m->nbody; ++b) {
      const int i = imported.model.FindBody(mj_id2name(m, mjOBJ_BODY, b));
      ASSERT_GE(i, 0) << mj_id2name(m, mjOBJ_BODY, b);
      const Eigen::Vector3d p(d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]);
      EXPECT_LT((imported.model.bodies[i].p_WB_home - p).norm(), 1e-9) << imported.model.bodies[i].name;
    }
    mj_deleteData(d);
    mj_deleteModel(m);
    // The closed form, and the round trip through ccma's MJCF.
    const ImportedRobot again = ImportExport(imported.model);
    for (const Eigen::VectorXd& u : f.controls) {
      ForwardProblem forward(imported.model), twice(again.model);
      ASSERT_TRUE(forward.Assemble(u).assembled) << u.transpose();
      ASSERT_TRUE(twice.Assemble(u).assembled) << u.transpose();
      EXPECT_LT((forward.end_effector().position - f.hand(u)).norm(), 1e-9) << u.transpose();
      EXPECT_LT((twice.end_effector().position - f.hand(u)).norm(), 1e-9) << u.transpose();
    }
  }
}

// Genesis' four-bar closed by a weld (with an anchor) instead: a 6d closure
// whose two frames coincide at qpos0 (MuJoCo 2.2's weld: body2's anchor at
// the relative pose in body1).
TEST(MjcfImport, AWeldIsASixDimensionalClosureAtItsRelativePose) {
  const RobotDescription robot =
      ReadMjcf(std::string(CCMA_TEST_DATA_DIR) + "/corpus/mjcf/genesis/four_bar_linkage_weld.xml", {});
  ASSERT_EQ(robot.closures.size(), 1u);
  const RobotClosure& weld = robot.closures[0];
  EXPECT_TRUE(weld.six_d);
  EXPECT_LT((weld.X_WA.translation() - weld.X_WB.translation()).norm(), 1e-12);
  EXPECT_LT((weld.X_WA.linear() - weld.X_WB.linear()).norm(), 1e-12);
  EXPECT_TRUE(robot.actuated.empty());  // it has no actuator: the user names the motors
}

}  // namespace mjcf_import_test
}  // namespace ccma
