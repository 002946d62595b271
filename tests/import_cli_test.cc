// `ccma import` from the command line: the contract's JSON, a planar-base
// robot written by hand, and hostile sources (exit 2, file, line, element and
// name in one line on stderr, nothing on stdout).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ccma/internal/format.h"
#include "ccma/joint_coordinates.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "tests/tool_run.h"

namespace ccma {
namespace import_cli_test {

using testing::RunTool;
using testing::ToolRun;

const std::string kRobots = std::string(CCMA_MODELS_DIR) + "/robots/example-parallel-robots/";

class ImportCli : public ::testing::Test {
 protected:
  ImportCli() {
    dir_ = std::filesystem::path(ccma::testing::TestDir()) /
           ("ccma_import_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  ~ImportCli() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string Out() const { return (dir_ / "out.yaml").string(); }
  // Runs import and expects exit 2 with `needle` on stderr, nothing on stdout, no output file.
  void ExpectRefused(const std::vector<std::string>& args, const std::string& needle) const {
    const ToolRun r = RunTool(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(Out()));
  }
  std::filesystem::path dir_;
};

// An arm on a planar base: base (planar from world), shoulder (revolute,
// actuated, limited), upper arm 0.5 m along x, end-effector at its tip.
constexpr char kArmOnBase[] = R"(<?xml version="1.0"?>
<robot name="arm_on_base">
  <link name="world"/>
  <link name="base"/>
  <link name="upper"/>
  <joint name="drive" type="planar">
    <parent link="world"/><child link="base"/>
    <origin xyz="1 2 0" rpy="0 0 0.5"/><axis xyz="0 0 1"/>
    <limit effort="1" velocity="1"/>
  </joint>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
)";

TEST_F(ImportCli, PlanarJointMakesAMobileBaseAndControlsFollowTheSource) {
  const std::string urdf = Write("arm.urdf", kArmOnBase);
  const ToolRun r = RunTool({"import", "--from=" + urdf, "--actuated=drive,shoulder",
                             "--end_effector=upper:0.5,0,0", "--controlled=x,y,z", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["bodies"], 2);
  EXPECT_EQ(j["closures"], 0);
  EXPECT_EQ(j["actuated"], nlohmann::json({"drive", "shoulder"}));
  EXPECT_EQ(j["assembled"], true);
  const std::vector<double> controls = j["controls"];
  ASSERT_EQ(controls.size(), 4u);
  EXPECT_NEAR(controls[0], 1, 1e-12);
  EXPECT_NEAR(controls[1], 2, 1e-12);
  EXPECT_NEAR(controls[2], 0.5, 1e-12);
  EXPECT_NEAR(controls[3], 0, 1e-12);
  // The written model: shoulder at 0.4 rad about the base's y axis puts the
  // tip at base + Rz(0.5) (0.5 cos 0.4, 0, 0.3 - 0.5 sin 0.4).
  const Model model = LoadModel(Out());
  ASSERT_EQ(model.num_bases(), 1);
  ASSERT_TRUE(model.joints[0].limited);
  ForwardProblem problem(model);
  Eigen::VectorXd u(4);
  u << 1, 2, 0.5, 0.4;
  ASSERT_TRUE(problem.Assemble(u).assembled);
  const Eigen::Vector3d local(0.5 * std::cos(0.4), 0, 0.3 - 0.5 * std::sin(0.4));
  const Eigen::Vector3d expected =
      Eigen::Vector3d(1, 2, 0) + Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * local;
  EXPECT_LT((problem.end_effector().position - expected).norm(), 1e-9);
}

// kArmOnBase with mesh visuals: `base` on the base link, each of `upper` on the upper arm.
std::string ArmWithMeshes(const std::string& base, const std::vector<std::string>& upper) {
  const auto visual = [](const std::string& file) {
    return "<visual><geometry><mesh filename=\"" + file + "\"/></geometry></visual>";
  };
  std::string text = kArmOnBase;
  text.replace(text.find("<link name=\"base\"/>"), 19, "<link name=\"base\">" + visual(base) + "</link>");
  std::string visuals;
  for (const std::string& file : upper) visuals += visual(file);
  text.replace(text.find("<link name=\"upper\"/>"), 20, "<link name=\"upper\">" + visuals + "</link>");
  return text;
}

void WriteStl(const std::filesystem::path& path) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\n"
                         "endloop\nendfacet\nendsolid t\n";
}

// The `file` of every mesh of the model file at `path`, in order.
std::vector<std::string> MeshFilesOf(const std::string& path) {
  std::vector<std::string> files;
  for (const Body& body : LoadModel(path).bodies) {
    for (const BodyMesh& mesh : body.meshes) files.push_back(mesh.file);
  }
  return files;
}

const std::vector<std::string> kArmFlags = {"--actuated=drive,shoulder", "--end_effector=upper:0.5,0,0",
                                            "--controlled=x,y,z"};

TEST_F(ImportCli, MeshPathsAreWrittenRelativeToTheModelFileNeverAbsolute) {
  // A relative uri, file:// (absolute) and package://PKG/../../ (out of the package).
  const std::filesystem::path robot = dir_ / "ws" / "robot";
  WriteStl(robot / "meshes" / "base.stl");
  WriteStl(dir_ / "elsewhere" / "upper.stl");
  WriteStl(dir_ / "stolen.stl");
  std::filesystem::create_directories(robot);
  std::ofstream(robot / "arm.urdf") << ArmWithMeshes(
      "meshes/base.stl", {"file://" + (dir_ / "elsewhere" / "upper.stl").string(), "package://robot/../../stolen.stl"});
  std::filesystem::create_directories(dir_ / "out");
  const std::string out = (dir_ / "out" / "arm.yaml").string();
  std::vector<std::string> args = {"import", "--from=" + (robot / "arm.urdf").string(), "--out=" + out};
  args.insert(args.end(), kArmFlags.begin(), kArmFlags.end());
  const ToolRun r = RunTool(args);
  ASSERT_EQ(r.status, 0) << r.err;
  // The bodies in model order: the arm, then the base.
  EXPECT_EQ(MeshFilesOf(out), (std::vector<std::string>{"../elsewhere/upper.stl", "../stolen.stl",
                                                         "../ws/robot/meshes/base.stl"}));
  const std::string text = testing::Slurp(out);
  for (std::size_t at = text.find("file: "); at != std::string::npos; at = text.find("file: ", at + 1)) {
    const std::string line = text.substr(at, text.find('\n', at) - at);
    EXPECT_EQ(line.find(dir_.string()), std::string::npos) << line;
    EXPECT_EQ(line.find("file://"), std::string::npos) << line;
  }
  EXPECT_NE(r.err.find("ccma import: warning: " + (robot / "arm.urdf").string() +
                       ": 3 mesh file(s) lie outside the model file's folder (the first: "
                       "'../elsewhere/upper.stl'): `ccma view --meshes` reads them only with --mesh_root"),
            std::string::npos) << r.err;
  // As the warning says: view refuses them, and reads them with their folder given.
  const std::string page = (dir_ / "out" / "arm.html").string();
  EXPECT_EQ(RunTool({"view", "--model=" + out, "--meshes", "--out=" + page}).status, 2);
  const ToolRun view = RunTool({"view", "--model=" + out, "--meshes", "--mesh_root=" + dir_.string(), "--out=" + page});
  ASSERT_EQ(view.status, 0) << view.err;
  EXPECT_EQ(nlohmann::json::parse(view.out)["mesh_files"], 3);
  EXPECT_EQ(testing::Slurp(page).find(dir_.string()), std::string::npos);
}

TEST_F(ImportCli, ModelImportedBesideItsRobotViewsItsMeshesAndMovesWithThem) {
  // `ccma import --from=robot/arm.urdf --out=arm.yaml` and --out=robot/arm.yaml:
  // both hold the meshes in their folder, with no flag.
  const std::filesystem::path robot = dir_ / "robot";
  WriteStl(robot / "meshes" / "base.stl");
  WriteStl(robot / "meshes" / "upper.stl");
  std::ofstream(robot / "arm.urdf") << ArmWithMeshes("meshes/base.stl", {"package://robot/meshes/upper.stl"});
  for (const std::filesystem::path& out : {dir_ / "arm.yaml", robot / "arm.yaml"}) {
    std::vector<std::string> args = {"import", "--from=" + (robot / "arm.urdf").string(), "--out=" + out.string()};
    args.insert(args.end(), kArmFlags.begin(), kArmFlags.end());
    const ToolRun r = RunTool(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("mesh"), std::string::npos) << r.err;
  }
  EXPECT_EQ(MeshFilesOf((dir_ / "arm.yaml").string()),
            (std::vector<std::string>{"robot/meshes/upper.stl", "robot/meshes/base.stl"}));
  EXPECT_EQ(MeshFilesOf((robot / "arm.yaml").string()),
            (std::vector<std::string>{"meshes/upper.stl", "meshes/base.stl"}));
  // Moved elsewhere with its meshes, the model still finds them.
  const std::filesystem::path moved = dir_ / "moved";
  std::filesystem::rename(robot, moved);
  const std::string page = (dir_ / "arm.html").string();
  const ToolRun view = RunTool({"view", "--model=" + (moved / "arm.yaml").string(), "--meshes", "--out=" + page});
  ASSERT_EQ(view.status, 0) << view.err;
  EXPECT_EQ(nlohmann::json::parse(view.out)["mesh_files"], 2);
  EXPECT_EQ(testing::Slurp(page).find(dir_.string()), std::string::npos);
}

TEST_F(ImportCli, FiveBarJsonAsTheContractSays) {
  const ToolRun r = RunTool({"import", "--from=" + kRobots + "5bar_linkage/robot.urdf",
                             "--closures=" + kRobots + "5bar_linkage/robot.yaml", "--end_effector=effector",
                             "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"out", "bodies", "joints", "closures", "actuated", "controlled", "controlled_chosen",
                          "assembled", "residual_energy", "controls"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["closures"], 1);
  EXPECT_LT(j["residual_energy"].get<double>(), 1e-24);
  EXPECT_EQ(j["controls"], nlohmann::json({0.0, 0.0}));
}

// The five-bar's two motors move its effector in the world's y-z plane:
// without --controlled, import controls y and z and says so; check then
// counts exactly 2 end-effector DOF, without a warning, and control reaches
// a target given as those two components. --controlled=x,y,z, which the
// motors cannot move, is refused naming the ones they move.
TEST_F(ImportCli, WithoutControlledTheComponentsTheMotorsMoveAreChosen) {
  const std::string five = kRobots + "5bar_linkage/";
  const std::vector<std::string> args = {"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                                         "--end_effector=effector", "--out=" + Out()};
  const ToolRun r = RunTool(args);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["controlled"], nlohmann::json({"y", "z"}));
  EXPECT_EQ(j["controlled_chosen"], true);
  EXPECT_NE(r.err.find("ccma import: controlled components chosen: y,z (the controls move 2 end-effector DOF at "
                       "home; choose others with --controlled)\n"),
            std::string::npos)
      << r.err;
  const ToolRun check = RunTool({"check", "--model=" + Out()});
  ASSERT_EQ(check.status, 0) << check.err;
  const nlohmann::json mobility = nlohmann::json::parse(check.out);
  EXPECT_EQ(mobility["end_effector_dof"], 2);
  EXPECT_EQ(mobility["controlled"], nlohmann::json({"y", "z"}));
  EXPECT_EQ(check.err.find("end-effector DOF at home, fewer than"), std::string::npos) << check.err;
  // A target 5 mm off home in y and z, given as its two components.
  const Model model = LoadModel(Out());
  const Eigen::Vector3d home = model.end_effector.p_W_home;
  const std::string target = "--target=" + std::to_string(home.y() + 0.005) + "," + std::to_string(home.z() - 0.005);
  const ToolRun control = RunTool({"control", "--model=" + Out(), target});
  ASSERT_EQ(control.status, 0) << control.err;
  EXPECT_EQ(nlohmann::json::parse(control.out)["converged"], true) << control.err;
  std::filesystem::remove(Out());
  std::vector<std::string> given = args;
  given.push_back("--controlled=z,y");
  const ToolRun same = RunTool(given);
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_EQ(nlohmann::json::parse(same.out)["controlled"], nlohmann::json({"y", "z"}));
  EXPECT_EQ(nlohmann::json::parse(same.out)["controlled_chosen"], false);
  EXPECT_EQ(same.err.find("chosen"), std::string::npos) << same.err;
  std::filesystem::remove(Out());
  given.back() = "--controlled=x,y,z";
  ExpectRefused(given, "5bar_linkage/robot.urdf: the controls cannot move the controlled components x y z "
                       "independently at home (rank 2 of 3): they move 2 end-effector DOF, for example y z (the "
                       "default when none are given)");
  given.back() = "--controlled=x";
  ExpectRefused(given, "the controlled components x independently at home (rank 0 of 1)");
  // The frame the motors are mounted on: they move none of its components.
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml", "--end_effector=built",
                 "--out=" + Out()},
                "5bar_linkage/robot.urdf: the controls move no component of the end-effector 'built' at home: "
                "choose another end-effector link");
}

// Components stored by `ccma export` are the exported model's own: kept
// (the round trip gives back the same model), with a warning when the
// motors cannot move them.
TEST_F(ImportCli, StoredComponentsAreKeptWithAWarningWhenTheMotorsCannotMoveThem) {
  const std::string five = kRobots + "5bar_linkage/";
  ASSERT_EQ(RunTool({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                     "--end_effector=effector", "--out=" + Out()})
                .status,
            0);
  std::string text = testing::Slurp(Out());
  const std::size_t at = text.find("controlled: [y, z]");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 18, "controlled: [x, y, z]");
  const std::string model = Write("over.yaml", text);
  const std::string sdf = (dir_ / "over.sdf").string();
  ASSERT_EQ(RunTool({"export", "--model=" + model, "--format=sdf", "--out=" + sdf}).status, 0);
  const ToolRun r = RunTool({"import", "--from=" + sdf, "--out=" + (dir_ / "again.yaml").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["controlled"], nlohmann::json({"x", "y", "z"}));
  EXPECT_EQ(j["controlled_chosen"], false);
  EXPECT_NE(r.err.find("over.sdf: the stored end-effector components: the controls cannot move the controlled "
                       "components x y z independently at home (rank 2 of 3): they move 2 end-effector DOF, for "
                       "example y z\n"),
            std::string::npos)
      << r.err;
}

// cassie_like's two rods between ball joints spin freely about their axes
// (idle motions: `check` names them). Control's controls, assembled from
// home, give the same configuration up to those spins: no "several assembly
// branches" warning, and from_home names the spinning bodies. (A real
// branch still warns: Branches.ControlWarnsAndSimulateFromReproduces.)
TEST_F(ImportCli, IdleSpinsOfImportedRodsAreNotAssemblyBranches) {
  const std::string cassie = kRobots + "cassie_like/";
  const ToolRun r = RunTool({"import", "--from=" + cassie + "robot.urdf", "--closures=" + cassie + "robot.yaml",
                             "--end_effector=foot", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const Eigen::Vector3d home = LoadModel(Out()).end_effector.p_W_home;
  const std::string target = "--target=" + std::to_string(home.x() + 0.01) + "," + std::to_string(home.y() + 0.01) +
                             "," + std::to_string(home.z() + 0.005) + ",0,0,0";
  const ToolRun c = RunTool({"control", "--model=" + Out(), target});
  ASSERT_EQ(c.status, 0) << c.err;
  const nlohmann::json control = nlohmann::json::parse(c.out);
  EXPECT_EQ(control["converged"], true) << c.err;
  EXPECT_EQ(c.err.find("assemble to another configuration"), std::string::npos) << c.err;
  EXPECT_EQ(control.contains("warning"), false);
  const nlohmann::json& from_home = control["from_home"];
  EXPECT_EQ(from_home["reproducible"], true);
  EXPECT_LT(from_home["end_effector_distance_m"].get<double>(), 1e-9);
  EXPECT_LT(from_home["max_state_difference"].get<double>(), 1e-9);
  std::vector<std::string> idle = from_home["idle_bodies"];
  std::sort(idle.begin(), idle.end());
  EXPECT_EQ(idle, (std::vector<std::string>{"closedloop1_A", "closedloop1_B", "closedloop2_A", "closedloop2_B",
                                             "half_hachil_rode", "half_hachil_rode_2", "half_planta_rode",
                                             "half_planta_rode_2"}));
}

TEST_F(ImportCli, ClosureFileQuirksOfTheCollectionAreRead) {
  // Upper-case types ('3D', as kangaroo_like_2legs writes) and a joint_name
  // the URDF does not have (as disney_robot's): read, the latter with a warning.
  const std::string five = kRobots + "5bar_linkage/";
  const std::string closures = Write("q.yaml", "closed_loop: [['closedloop1_A', 'closedloop1_B']]\ntype: ['6D']\n"
                                               "name_mot: ['mot1', 'mot2']\njoint_name: ['no_such_joint']\n"
                                               "joint_type: ['SPHERICAL']\n");
  const ToolRun r = RunTool({"import", "--from=" + five + "robot.urdf", "--closures=" + closures,
                             "--end_effector=effector", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("ccma import: warning: " + (dir_ / "q.yaml").string() +
                       ":4: joint_name: no joint 'no_such_joint' in"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["closures"], 1);
}

// --collision_radius gives the five-bar capsules (JSON counts them), so that
// an --obstacles ledge under its effector is measured by check, at 0.05 m
// minus the radius; a radius out of range is refused.
TEST_F(ImportCli, CollisionRadiusGivesCapsulesThatObstaclesAreMeasuredAgainst) {
  const std::string five = kRobots + "5bar_linkage/";
  const std::vector<std::string> args = {"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                                         "--end_effector=effector", "--out=" + Out()};
  for (const char* bad : {"-0.01", "nan", "11", "1e-5"}) {
    std::vector<std::string> hostile = args;
    hostile.push_back(std::string("--collision_radius=") + bad);
    ExpectRefused(hostile, "--collision_radius");
  }
  std::vector<std::string> with = args;
  with.push_back("--collision_radius=0.02");
  const ToolRun r = RunTool(with);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["collision_capsules"], 10);  // built 2, rod 1, rod_2 1, rod_3 1, end_rod 2, 3 one-point bodies
  EXPECT_EQ(j["collision_ignored_pairs"], 3);
  const Model m = LoadModel(Out());
  const Eigen::Vector3d p = m.end_effector.p_W_home;
  const std::string obstacles =
      Write("ledge.yaml", "obstacles:\n  - {name: ledge, box: {center: [" + std::to_string(p.x()) + ", " +
                              std::to_string(p.y()) + ", " + std::to_string(p.z() - 0.075) +
                              "], size: [1, 1, 0.05], yaw: 0}}\n");
  const ToolRun check = RunTool({"check", "--model=" + Out(), "--obstacles=" + obstacles});
  ASSERT_EQ(check.status, 0) << check.err;
  const nlohmann::json c = nlohmann::json::parse(check.out)["clearance"];
  EXPECT_NEAR(c["min"].get<double>(), 0.03, 2e-6);  // std::to_string keeps 6 decimals
  EXPECT_EQ(c["pair"][1], "ledge");
  const ToolRun without = RunTool({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                                   "--end_effector=effector", "--out=" + Out()});
  ASSERT_EQ(without.status, 0) << without.err;
  EXPECT_FALSE(nlohmann::json::parse(without.out).contains("collision_capsules"));
}

TEST_F(ImportCli, HostileSourcesAreRefusedWithFileLineAndName) {
  const std::string five = kRobots + "5bar_linkage/";
  std::ifstream in(five + "robot.urdf");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string truncated = Write("truncated.urdf", text.substr(0, text.size() / 2));
  ExpectRefused({"import", "--from=" + truncated, "--end_effector=effector", "--out=" + Out()},
                "truncated.urdf:");
  const std::string unknown_frame = Write("c.yaml", "closed_loop: [['closedloop1_A', 'nowhere']]\ntype: ['6d']\n"
                                                    "name_mot: ['mot1', 'mot2']\n");
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + unknown_frame, "--end_effector=effector",
                 "--out=" + Out()},
                "c.yaml:1: closed_loop[0]: unknown frame 'nowhere'");
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                 "--actuated=mot1,mot9", "--end_effector=effector", "--out=" + Out()},
                "actuated joint 'mot9'");
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                 "--end_effector=nolink", "--out=" + Out()},
                "end-effector link 'nolink'");
  // A controlled component given twice is a typo, not a request (issue 34).
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + five + "robot.yaml",
                 "--end_effector=effector", "--controlled=x,y,x", "--out=" + Out()},
                "controlled component 'x' given twice");
  // The base welded to the effector cannot be assembled with both motors held.
  const std::string impossible = Write("i.yaml", "closed_loop: [['built', 'effector']]\ntype: ['6d']\n"
                                                 "name_mot: ['mot1', 'mot2']\n");
  ExpectRefused({"import", "--from=" + five + "robot.urdf", "--closures=" + impossible, "--end_effector=effector",
                 "--out=" + Out()},
                "cannot assemble closure 'built__effector'");
  std::string floating = kArmOnBase;
  floating.replace(floating.find("type=\"revolute\""), 15, "type=\"floating\"");
  ExpectRefused({"import", "--from=" + Write("f.urdf", floating), "--actuated=drive", "--end_effector=upper",
                 "--out=" + Out()},
                "f.urdf:11: joint 'shoulder': joint type not supported");
  std::string deep = "<robot name=\"r\">";
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  ExpectRefused({"import", "--from=" + Write("deep.urdf", deep), "--end_effector=x", "--out=" + Out()},
                "deep.urdf:1: XML elements nested more than 100 deep");
  ExpectRefused({"import", "--from=" + Write("nan.urdf", std::string(kArmOnBase).replace(
                                                             std::string(kArmOnBase).find("1 2 0"), 5, "nan 2 0")),
                 "--actuated=drive", "--end_effector=upper", "--out=" + Out()},
                "nan.urdf");
}

// Issue 34: `<?x >` hid 100,000 nested elements from the nesting check
// (TinyXML then overflowed the stack) in both formats; names from the file
// reached the terminal raw (escape sequences, fake lines) and in full; a
// 100,000-link URDF was read and assembled for seconds before the loader
// refused "a model file" the user never gave.
TEST_F(ImportCli, HostileRobotFilesAreRefusedEarlyNamingTheFile) {
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  ExpectRefused({"import", "--from=" + Write("hidden.urdf", "<?x >" + deep + "<!-- ?> --><robot name=\"r\"/>"),
                 "--end_effector=a", "--out=" + Out()},
                "hidden.urdf:1: expected the root element <robot>, found a processing instruction ('<?')");
  ExpectRefused({"import", "--from=" + Write("hidden.sdf", "<?x >" + deep + "<!-- ?> --><sdf version=\"1.7\"/>"),
                 "--end_effector=a", "--out=" + Out()},
                "hidden.sdf:1: expected the root element <sdf>, found a processing instruction ('<?')");
  std::string escapes = kArmOnBase;
  const std::string shoulder = "\"shoulder\" type=\"revolute\"";
  escapes.replace(escapes.find(shoulder), shoulder.size(), "\"sh&#x1b;[31m&#10;oulder\" type=\"floating\"");
  ExpectRefused({"import", "--from=" + Write("e.urdf", escapes), "--actuated=drive", "--end_effector=upper",
                 "--out=" + Out()},
                "e.urdf:11: joint 'sh\\x1b[31m\\x0aoulder': joint type not supported");
  ExpectRefused({"import", "--from=" + Write("ok.urdf", kArmOnBase), "--actuated=" + std::string(100000, 'm'),
                 "--end_effector=upper", "--out=" + Out()},
                "--actuated: empty or overlong name in 'mmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmm...' (100000 bytes)");
  std::string chain = "<robot name=\"chain\"><link name=\"l0\"/>";
  for (int i = 1; i <= 2000; ++i) {
    const std::string n = std::to_string(i), p = std::to_string(i - 1);
    chain += "<link name=\"l" + n + "\"/><joint name=\"j" + n + "\" type=\"fixed\"><parent link=\"l" + p +
             "\"/><child link=\"l" + n + "\"/></joint>";
  }
  ExpectRefused({"import", "--from=" + Write("chain.urdf", chain + "</robot>"), "--end_effector=l0", "--out=" + Out()},
                "chain.urdf: 2001 links and 2000 joints: ccma imports at most 2000 links and 2000 joints");
  std::string huge = "<robot name=\"huge\">";
  for (int i = 0; i < 99998; ++i) huge += "<link name=\"l" + std::to_string(i) + "\"/>";
  ExpectRefused({"import", "--from=" + Write("huge.urdf", huge + "</robot>"), "--end_effector=l0", "--out=" + Out()},
                "huge.urdf: 99998 links and 0 joints: ccma imports at most 2000 links");
}


// A four-bar whose loop cannot close with the crank at its source position:
// crank 1 m from the origin and coupler 5.5 m along +x, rocker 2 m about
// (4, 0, 0) along +y at zero, so the closure's frames (the coupler's and the
// rocker's far ends, (6.5, 0) and (4, 2)) are sqrt(10.25) m apart, and the
// crank end (1, 0) is 3 m from the rocker pivot, less than 5.5 - 2: the loop
// closes only with the crank turned by at least acos(0.59375) = 0.936 rad
// (|(cos t, sin t) - (4, 0)| >= 3.5).
constexpr char kGappedFourBar[] = R"(<?xml version="1.0"?>
<robot name="gapped">
  <link name="world"/>
  <link name="crank"/><link name="coupler"/><link name="coupler_end"/><link name="rocker"/><link name="rocker_end"/>
  <joint name="drive" type="continuous"><parent link="world"/><child link="crank"/><axis xyz="0 0 1"/></joint>
  <joint name="knee" type="continuous"><parent link="crank"/><child link="coupler"/>
    <origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="coupler_tip" type="fixed"><parent link="coupler"/><child link="coupler_end"/><origin xyz="5.5 0 0"/></joint>
  <joint name="hip" type="continuous"><parent link="world"/><child link="rocker"/>
    <origin xyz="4 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="rocker_tip" type="fixed"><parent link="rocker"/><child link="rocker_end"/><origin xyz="0 2 0"/></joint>
</robot>
)";
constexpr char kGappedClosures[] = "closed_loop: [['coupler_end', 'rocker_end']]\ntype: ['3d']\nname_mot: ['drive']\n";

TEST_F(ImportCli, GapsAndMotorMovesAreReportedAndStrictRefusesThem) {
  const std::string urdf = Write("gapped.urdf", kGappedFourBar);
  const std::string closures = Write("gapped.yaml", kGappedClosures);
  const std::vector<std::string> args = {"import", "--from=" + urdf, "--closures=" + closures,
                                         "--end_effector=coupler:2,0,0", "--out=" + Out()};
  const ToolRun r = RunTool(args);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["closure_gaps"].size(), 1u);
  EXPECT_EQ(j["closure_gaps"][0]["name"], "coupler_end__rocker_end");
  EXPECT_NEAR(j["closure_gaps"][0]["gap_m"].get<double>(), std::sqrt(10.25), 1e-12);
  EXPECT_EQ(j["closure_gaps"][0]["gap_rad"].get<double>(), 0.0);  // 3d: origins only
  ASSERT_EQ(j["motor_moves"].size(), 1u);
  EXPECT_EQ(j["motor_moves"][0]["name"], "drive");
  const double move = j["motor_moves"][0]["move"].get<double>();
  EXPECT_GE(std::abs(move), std::acos(0.59375) - 1e-9);
  EXPECT_NEAR(j["controls"][0].get<double>(), move, 1e-12);  // the control is the motor's source-relative position
  EXPECT_NE(r.err.find("closure 'coupler_end__rocker_end': its frames are 3.20156 m and 0 rad apart"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("motor 'drive' moved " + FormatG(move)), std::string::npos) << r.err;
  std::filesystem::remove(Out());
  std::vector<std::string> strict = args;
  strict.insert(strict.end() - 1, "--strict");
  ExpectRefused(strict, "--strict: the import would change the mechanism: closure 'coupler_end__rocker_end'");
}

// A loop the source poses closed: no gap, no move, nothing said.
TEST_F(ImportCli, AClosedSourceHasNoGapsAndStrictAcceptsIt) {
  const ToolRun r = RunTool({"import", "--from=" + std::string(CCMA_TEST_DATA_DIR) + "/four_bar_loop.sdf",
                             "--actuated=crank", "--end_effector=coupler:4.8,0,0", "--strict", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // SDFormat closes its loops with joints, each posed once: gap 0, named.
  ASSERT_EQ(j["closure_gaps"].size(), 1u);
  EXPECT_EQ(j["closure_gaps"][0]["gap_m"].get<double>(), 0.0);
  EXPECT_EQ(j["closure_gaps"][0]["gap_rad"].get<double>(), 0.0);
  EXPECT_EQ(j["closures"].get<int>(), 1);
  ASSERT_EQ(j["motor_moves"].size(), 1u);
  EXPECT_EQ(j["motor_moves"][0]["move"].get<double>(), 0.0);
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
}


// The four-bar of four_bar_loop.sdf as a URDF posed assembled, its loop
// closed between the coupler's frame (at its pivot A on the crank, x toward
// B) and the rocker's far end B: the closing point lies 4.8 m along the
// coupler's x, which the closure file's offset says.
constexpr char kPosedFourBar[] = R"(<?xml version="1.0"?>
<robot name="posed">
  <link name="world"/>
  <link name="crank"/><link name="coupler"/><link name="rocker"/><link name="rocker_end"/>
  <joint name="drive" type="continuous"><parent link="world"/><child link="crank"/>
    <origin xyz="-2 0 0" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 1"/></joint>
  <joint name="knee" type="continuous"><parent link="crank"/><child link="coupler"/>
    <origin xyz="1 0 0" rpy="0 0 -1.3895166182633261"/><axis xyz="0 0 1"/></joint>
  <joint name="hip" type="continuous"><parent link="world"/><child link="rocker"/>
    <origin xyz="2 0 0" rpy="0 0 1.2018068856832935"/><axis xyz="0 0 1"/></joint>
  <joint name="rocker_tip" type="fixed"><parent link="rocker"/><child link="rocker_end"/><origin xyz="2 0 0"/></joint>
</robot>
)";

// The model at `path` moves as the SDFormat four-bar (four_bar_loop.sdf,
// crank actuated, end-effector at B) at several crank angles, to 1e-9 m.
void ExpectTheSdformatFourBar(const std::string& path, const std::filesystem::path& dir) {
  const std::string sdf_path = (dir / "sdf.yaml").string();
  const ToolRun sdf = RunTool({"import", "--from=" + std::string(CCMA_TEST_DATA_DIR) + "/four_bar_loop.sdf",
                               "--actuated=crank", "--end_effector=coupler:4.8,0,0", "--out=" + sdf_path});
  ASSERT_EQ(sdf.status, 0) << sdf.err;
  const Model model = LoadModel(path), sdf_model = LoadModel(sdf_path);
  ForwardProblem a(model), b(sdf_model);
  for (const double u : {0.0, 0.4, -0.9, 2.0}) {
    const Eigen::VectorXd controls = Eigen::VectorXd::Constant(1, u);
    ASSERT_TRUE(a.Assemble(controls).assembled) << u;
    ASSERT_TRUE(b.Assemble(controls).assembled) << u;
    EXPECT_LT((a.end_effector().position - b.end_effector().position).norm(), 1e-9) << "u = " << u;
  }
}

TEST_F(ImportCli, AClosureOffsetClosesAGappedPairExactly) {
  const std::string urdf = Write("posed.urdf", kPosedFourBar);
  const std::string with_offset = Write("offset.yaml", "closed_loop: [['coupler', 'rocker_end']]\ntype: ['3d']\n"
                                                       "name_mot: ['drive']\noffset: [[4.8, 0, 0, 0, 0, 0]]\n");
  const ToolRun r = RunTool({"import", "--from=" + urdf, "--closures=" + with_offset, "--end_effector=coupler:4.8,0,0",
                             "--strict", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["closure_gaps"][0]["gap_m"].get<double>(), 1e-12);
  EXPECT_EQ(j["motor_moves"][0]["move"].get<double>(), 0.0);
  // The same mechanism as the SDFormat four-bar, at every crank angle.
  ExpectTheSdformatFourBar(Out(), dir_);
  // Without the offset the pair is 4.8 m apart: another mechanism, one that
  // cannot be assembled even with the motor free.
  std::filesystem::remove(Out());
  const std::string without = Write("plain.yaml", "closed_loop: [['coupler', 'rocker_end']]\ntype: ['3d']\n"
                                                  "name_mot: ['drive']\n");
  ExpectRefused({"import", "--from=" + urdf, "--closures=" + without, "--end_effector=coupler:4.8,0,0",
                 "--out=" + Out()},
                "cannot assemble closure 'coupler__rocker_end'");
}

TEST_F(ImportCli, AMalformedOffsetNamesItsLine) {
  const std::string urdf = Write("posed.urdf", kPosedFourBar);
  const std::string bad = Write("bad.yaml", "closed_loop: [['coupler', 'rocker_end']]\ntype: ['3d']\n"
                                            "name_mot: ['drive']\noffset: [[4.8, 0, 0]]\n");
  ExpectRefused({"import", "--from=" + urdf, "--closures=" + bad, "--end_effector=coupler:4.8,0,0", "--out=" + Out()},
                "bad.yaml:4: offset[0]: must be [x, y, z, roll, pitch, yaw] (m, rad) or null");
}


// The four-bar of four_bar_loop.sdf as a URDF whose loop is closed the way
// Gazebo's own four-bar URDF closes it: kPosedFourBar without its rocker_end
// link, and a revolute joint inside <gazebo> at B = (2, 0, 0) in the rocker's
// frame.
constexpr char kGazeboLoopJoint[] = R"(  <gazebo>
    <joint name="coupler_rocker" type="revolute">
      <parent>coupler</parent><child>rocker</child>
      <pose>2 0 0 0 0 0</pose>
      <axis><xyz>0 0 1</xyz></axis>
    </joint>
  </gazebo>
)";

std::string GazeboFourBar() {
  std::string urdf = kPosedFourBar;
  const std::string tip = urdf.substr(urdf.find("  <joint name=\"rocker_tip\""));
  urdf.erase(urdf.find("  <joint name=\"rocker_tip\""), tip.find("\n") + 1);
  urdf.erase(urdf.find("<link name=\"rocker_end\"/>"), 25);
  urdf.insert(urdf.find("</robot>"), kGazeboLoopJoint);
  return urdf;
}

TEST_F(ImportCli, AUrdfLoopClosedTheGazeboWayIsTheSdformatFourBar) {
  const std::string urdf = Write("gazebo.urdf", GazeboFourBar());
  const ToolRun r = RunTool({"import", "--from=" + urdf, "--actuated=drive", "--end_effector=coupler:4.8,0,0",
                             "--strict", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["closures"], 1);  // one independent loop
  EXPECT_EQ(j["joints"], 4);
  ExpectTheSdformatFourBar(Out(), dir_);
  // A malformed one names its line.
  std::filesystem::remove(Out());
  std::string bad = GazeboFourBar();
  bad.replace(bad.find("type=\"revolute\">"), 16, "type=\"screw\">");
  ExpectRefused({"import", "--from=" + Write("bad.urdf", bad), "--actuated=drive", "--end_effector=coupler",
                 "--out=" + Out()},
                "bad.urdf:12: gazebo joint 'coupler_rocker': type 'screw' is not supported");
}


// An arm held horizontal by its shoulder motor: 2 kg at 0.5 m along it (its
// <inertial>), gravity -z, the shoulder turning about y: the motor holds
// m g l = 2 * 9.81 * 0.5 = 9.81 N*m.
constexpr char kHeavyArm[] = R"(<?xml version="1.0"?>
<robot name="heavy_arm">
  <link name="world"/>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="0.001" iyy="0.17" izz="0.17" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="shoulder" type="revolute"><parent link="world"/><child link="arm"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="100" velocity="1"/></joint>
</robot>
)";

TEST_F(ImportCli, MassesComeAlongAndStaticsWeighsThem) {
  const ToolRun r = RunTool({"import", "--from=" + Write("arm.urdf", kHeavyArm), "--actuated=shoulder",
                             "--end_effector=arm:1,0,0", "--controlled=z", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  const Model model = LoadModel(Out());
  const Body& arm = model.bodies[static_cast<std::size_t>(model.FindBody("arm"))];
  EXPECT_EQ(arm.inertia.mass, 2);
  EXPECT_LT((arm.R_WB_home * arm.inertia.com_B + arm.p_WB_home - Eigen::Vector3d(0.5, 0, 1)).norm(), 1e-12);
  // The inertial frame is turned 90 degrees about z: ixx and iyy swap in the world's axes.
  const Eigen::Matrix3d I_W = arm.R_WB_home * arm.inertia.inertia_B * arm.R_WB_home.transpose();
  EXPECT_LT((I_W - Eigen::Vector3d(0.17, 0.001, 0.17).asDiagonal().toDenseMatrix()).norm(), 1e-12);
  const ToolRun statics = RunTool({"statics", "--model=" + Out()});
  ASSERT_EQ(statics.status, 0) << statics.err;
  const nlohmann::json j = nlohmann::json::parse(statics.out);
  ASSERT_EQ(j["actuators"].size(), 1u);
  EXPECT_NEAR(std::abs(j["actuators"][0]["effort"].get<double>()), 2 * 9.81 * 0.5, 1e-9);
  // Exported back as <inertial> and imported again: the same mass, centre of mass and inertia.
  for (const std::string format : {"urdf", "sdf"}) {
    const std::string file = (dir_ / ("arm_out." + format)).string(), again = (dir_ / "again.yaml").string();
    const ToolRun e = RunTool({"export", "--model=" + Out(), "--format=" + format, "--out=" + file});
    ASSERT_EQ(e.status, 0) << e.err;
    std::vector<std::string> args = {"import", "--from=" + file, "--end_effector=arm:1,0,0", "--controlled=z",
                                     "--out=" + again};
    if (format == "urdf") args.insert(args.begin() + 2, "--closures=" + (dir_ / "arm_out.closures.yaml").string());
    const ToolRun i = RunTool(args);
    ASSERT_EQ(i.status, 0) << i.err;
    const Model back = LoadModel(again);
    const Body& b = back.bodies[static_cast<std::size_t>(back.FindBody("arm"))];
    EXPECT_EQ(b.inertia.mass, 2) << format;
    EXPECT_LT((b.R_WB_home * b.inertia.com_B + b.p_WB_home - Eigen::Vector3d(0.5, 0, 1)).norm(), 1e-12) << format;
    EXPECT_LT((b.R_WB_home * b.inertia.inertia_B * b.R_WB_home.transpose() - I_W).norm(), 1e-12) << format;
  }
}

TEST_F(ImportCli, ATonneTooManyDropsTheMassesAndSaysSo) {
  std::string heavy = kHeavyArm;
  heavy.replace(heavy.find("<mass value=\"2\"/>"), 17, "<mass value=\"654498\"/>");
  const ToolRun r = RunTool({"import", "--from=" + Write("heavy.urdf", heavy), "--actuated=shoulder",
                             "--end_effector=arm:1,0,0", "--controlled=z", "--out=" + Out()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("link 'arm': <inertial> mass 654498 kg is outside [0, 1e4] kg: no masses imported"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(LoadModel(Out()).bodies[0].inertia.mass, 0);
}

TEST_F(ImportCli, AModelFileRefusesAnInertiaThatIsNotPhysical) {
  std::ifstream in(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string model = text.str();
  const std::string post = "{name: post0, position: [0, 0.583012702, 0.1]}";
  const std::size_t at = model.find(post);
  ASSERT_NE(at, std::string::npos);
  model.replace(at, post.size(), "{name: post0, position: [0, 0.583012702, 0.1], mass: 1, inertia: [1, 1, 3, 0, 0, 0]}");
  const ToolRun r = RunTool({"check", "--model=" + Write("bad_inertia.yaml", model)});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(".inertia: violates the triangle inequality: principal moment 3 kg*m^2 exceeds the sum of the "
                       "other two (1 + 1)"),
            std::string::npos)
      << r.err;
}

}  // namespace import_cli_test
}  // namespace ccma
