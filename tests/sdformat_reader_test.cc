// The SDFormat reader (formats/sdformat_reader.h) on the bundled four-bar,
// whose joints form a loop, and on small files that exercise each element
// and each rejection; the four-bar imported (analyses/robot_import.h)
// against Freudenstein's closed form.
#include "formats/sdformat_reader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/robot_import.h"
#include "ccma/joint_coordinates.h"
#include "formats/model_loader.h"
#include "problems/forward_problem.h"
#include "tests/tool_run.h"

namespace ccma {
namespace sdformat_reader_test {

namespace fs = std::filesystem;

const std::string kFourBar = std::string(CCMA_TEST_DATA_DIR) + "/four_bar_loop.sdf";

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// An SDFormat 1.7 file holding `body` inside <model name="m">.
std::string Sdf(const std::string& body, const std::string& version = "1.7") {
  return "<?xml version=\"1.0\"?>\n<sdf version=\"" + version +
         "\" xmlns:ccma=\"https://ccma.dev/sdf\">\n<model name=\"m\">\n" + body +
         "</model>\n</sdf>\n";
}

// The message of the ModelError that reading `text` throws ("" if none).
std::string Rejection(const std::string& text) {
  try {
    ReadSdformatFromString(text, "/tmp/robot.sdf", {});
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

Eigen::Vector3d Point(const RobotDescription& robot, const std::string& joint) {
  return robot.joints[static_cast<std::size_t>(robot.FindJoint(joint))].X_WJ.translation();
}

Eigen::Vector3d InLink(const RobotDescription& robot, const std::string& link, double x) {
  return robot.links[static_cast<std::size_t>(robot.FindLink(link))].X_WL *
         Eigen::Vector3d(x, 0, 0);
}

TEST(SdformatReaderTest, FourBarLoopReadsWithItsWorldGeometry) {
  const RobotDescription robot = ReadSdformat(kFourBar, {"crank"});
  EXPECT_EQ(robot.name, "four_bar_loop");
  EXPECT_EQ(robot.source, kFourBar);
  ASSERT_EQ(robot.links.size(), 3u);
  EXPECT_EQ(robot.links[0].name, "driver");
  EXPECT_EQ(robot.links[1].name, "coupler");
  EXPECT_EQ(robot.links[2].name, "rocker");
  ASSERT_EQ(robot.joints.size(), 4u);
  const std::vector<std::vector<std::string>> expected = {{"crank", "world", "driver"},
                                                          {"world_rocker", "world", "rocker"},
                                                          {"driver_coupler", "driver", "coupler"},
                                                          {"coupler_rocker", "coupler", "rocker"}};
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(robot.joints[j].name, expected[j][0]);
    EXPECT_EQ(robot.joints[j].type, RobotJointType::kRevolute);
    EXPECT_EQ(robot.joints[j].parent, expected[j][1]);
    EXPECT_EQ(robot.joints[j].child, expected[j][2]);
    EXPECT_NEAR((robot.joints[j].axis_W - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-15);
    EXPECT_FALSE(robot.joints[j].limited);
    EXPECT_EQ(robot.joints[j].position, 0);
    EXPECT_GT(robot.joints[j].line, 0);
  }
  EXPECT_TRUE(robot.closures.empty());
  EXPECT_EQ(robot.actuated, std::vector<std::string>{"crank"});
  EXPECT_FALSE(robot.has_end_effector);
  // Ground pivots, crank pin A and coupler-rocker pin B: the bar lengths.
  const Eigen::Vector3d o2 = Point(robot, "crank"), o4 = Point(robot, "world_rocker");
  const Eigen::Vector3d a = Point(robot, "driver_coupler"), b = Point(robot, "coupler_rocker");
  EXPECT_NEAR((o2 - Eigen::Vector3d(-2, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((o4 - Eigen::Vector3d(2, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((o4 - o2).norm(), 4.0, 1e-12);
  EXPECT_NEAR((a - o2).norm(), 1.0, 1e-12);
  EXPECT_NEAR((b - a).norm(), 4.8, 1e-12);
  EXPECT_NEAR((b - o4).norm(), 2.0, 1e-12);
  // Each pin is where both links it joins put it: the links are assembled.
  EXPECT_NEAR((InLink(robot, "driver", 1.0) - a).norm(), 0, 1e-12);
  EXPECT_NEAR((InLink(robot, "coupler", 0.0) - a).norm(), 0, 1e-12);
  EXPECT_NEAR((InLink(robot, "coupler", 4.8) - b).norm(), 0, 1e-12);
  EXPECT_NEAR((InLink(robot, "rocker", 2.0) - b).norm(), 0, 1e-12);
  EXPECT_NEAR(b.x(), 2.7213461515864221, 1e-12);
  EXPECT_NEAR(b.y(), 1.8653846063456883, 1e-12);
  EXPECT_EQ(robot.links[0].meshes.size(), 0u);  // box visuals are not meshes
}

TEST(SdformatReaderTest, BundledFourBarIsTheTestedOne) {
  EXPECT_EQ(Slurp(std::string(CCMA_MODELS_DIR) + "/robots/four_bar_loop.sdf"), Slurp(kFourBar));
}

TEST(SdformatReaderTest, TruncatedFileNamesFileAndLine) {
  const std::string text = Slurp(kFourBar);
  const std::string path = testing::ScratchPath("sdformat_reader", "truncated.sdf");
  std::ofstream(path) << text.substr(0, text.find("<link name=\"rocker\">") + 40);
  try {
    ReadSdformat(path, {});
    FAIL() << "truncated file read";
  } catch (const ModelError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
    EXPECT_NE(message.find("not valid XML"), std::string::npos) << message;
  }
  EXPECT_NE(Rejection("<sdf version=\"1.7\"><model name=\"m\"><link name=\"a\"></model></sdf>")
                .find("/tmp/robot.sdf:1: not valid XML"),
            std::string::npos);
}

TEST(SdformatReaderTest, LibsdformatsOwnErrorsAreQuoted) {
  const std::string message =
      Rejection(Sdf("<link name=\"a\"/>\n<joint name=\"j\" "
                    "type=\"revolute\"><parent>world</parent><child>nowhere</child>"
                    "<axis><xyz>0 0 1</xyz></axis></joint>\n"));
  EXPECT_EQ(message.rfind("/tmp/robot.sdf: libsdformat: ", 0), 0u) << message;
  EXPECT_NE(
      message.find("Child frame with name[nowhere] specified by joint with name[j] not found"),
      std::string::npos)
      << message;
  EXPECT_NE(message.find("more"), std::string::npos)
      << message;  // libsdformat reported 8 errors; 3 shown
  const std::string duplicate = Rejection(Sdf("<link name=\"a\"/><link name=\"a\"/>"));
  EXPECT_NE(duplicate.find("libsdformat: "), std::string::npos) << duplicate;
  EXPECT_NE(duplicate.find("[a]"), std::string::npos) << duplicate;
  const std::string invalid =
      Rejection(Sdf("<link name=\"a\"/><joint name=\"j\" type=\"hinge\"><parent>world</parent>"
                    "<child>a</child></joint>"));
  EXPECT_NE(invalid.find("libsdformat: Joint type of hinge is invalid"), std::string::npos)
      << invalid;
}

TEST(SdformatReaderTest, UnsupportedJointTypeNamesTheJoint) {
  for (const std::string type : {"screw", "gearbox", "revolute2"}) {
    const std::string message = Rejection(
        Sdf("<link name=\"a\"/>\n<link name=\"b\"/>\n<joint name=\"twist\" type=\"" + type +
            "\"><parent>world</parent><child>a</child><axis><xyz>0 0 1</xyz></axis><axis2><xyz>1 0 "
            "0</xyz></axis2>"
            "</joint>\n"));
    EXPECT_NE(message.find("/tmp/robot.sdf:6: joint 'twist': type '" + type + "' is not supported"),
              std::string::npos)
        << message;
  }
}

TEST(SdformatReaderTest, OtherBadInputIsRejected) {
  EXPECT_NE(Rejection(Sdf("<link name=\"a\"/>", "1.3"))
                .find("/tmp/robot.sdf:2: sdf version '1.3': SDFormat 1.4 or later is needed"),
            std::string::npos);
  EXPECT_NE(Rejection("<robot name=\"r\"/>").find("not an SDFormat file"), std::string::npos);
  EXPECT_NE(Rejection(Sdf("<include><uri>/dev/zero</uri></include>"))
                .find(":4: <include> is not supported"),
            std::string::npos);
  std::string deep;
  for (int i = 0; i < 200; ++i) deep += "<a>";
  EXPECT_NE(Rejection(Sdf(deep)).find("nested more than 100 deep"), std::string::npos);
  EXPECT_NE(Rejection(Sdf("<link name=\"a\"><pose>1e5 0 0 0 0 0</pose></link>"))
                .find("link 'a': pose must be"),
            std::string::npos);
  EXPECT_NE(Rejection(Sdf("<link name=\"a\"/><link name=\"b\"/><joint name=\"p\" "
                          "type=\"planar\"><parent>a</parent>"
                          "<child>b</child></joint>"))
                .find("joint 'p': a planar joint must connect the ground"),
            std::string::npos);
  const std::string dir = testing::ScratchPath("sdformat_reader", "a_folder.sdf");
  fs::create_directories(dir);
  EXPECT_THROW(ReadSdformat(dir, {}), ModelError);
}

// Issue 34: markup that TinyXML and TinyXML-2 end at different places let a
// file that ccma's check saw as an empty <sdf> reach libsdformat as a URDF,
// whose <include> it followed (the included model's links came out; a FIFO
// hung it), and hid 100,000 nested elements from the nesting check (SIGSEGV).
TEST(SdformatReaderTest, FilesTheParsersReadDifferentlyAreRefusedBeforeLibsdformat) {
  const std::string dir = testing::ScratchPath("sdformat_reader", "other");
  fs::create_directories(dir);
  std::ofstream(dir + "/model.sdf") << Sdf("<link name=\"stolen\"/>\n");
  std::ofstream(dir + "/model.config") << "<?xml version=\"1.0\"?><model><name>other</name>"
                                          "<sdf version=\"1.7\">model.sdf</sdf></model>\n";
  const std::string bypass = "<?x ><sdf version=\"1.7\"/> <!-- ?> --><robot name=\"r\"><link name=\"a\"/><gazebo>"
                             "<include merge=\"true\"><uri>" + dir + "</uri></include></gazebo></robot>";
  EXPECT_NE(Rejection(bypass).find("/tmp/robot.sdf:1: expected the root element <sdf>, found a processing "
                                   "instruction ('<?')"),
            std::string::npos)
      << Rejection(bypass);
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  for (const std::string& hidden : {"<?x >" + deep + "<!-- ?> -->" + Sdf(""), "<!x >" + deep + Sdf(""),
                                    Sdf("<!-- ?> -->" + deep)}) {
    const std::string message = Rejection(hidden);
    EXPECT_EQ(message.rfind("/tmp/robot.sdf:", 0), 0u) << message.substr(0, 300);
    EXPECT_LT(message.size(), 400u);
  }
  EXPECT_NE(Rejection("<sdf version=\"1.7\"/>\n<robot name=\"r\"/>").find("/tmp/robot.sdf:2: found a '<' that does "
                                                                           "not start a tag after the root element"),
            std::string::npos);
  EXPECT_NE(Rejection(Sdf("<link name=\"a\"><![CDATA[x]]><include/></link>")).find(":4: <include> is not supported"),
            std::string::npos);
}

// Issue 34: libsdformat takes about 0.85 MB per <link> (4,000 took 3.4 GB):
// a file whose elements would take more than 1 GB is refused before it
// reads them, with the count and the estimate.
TEST(SdformatReaderTest, AFileTooLargeForLibsdformatIsRefusedBeforeIt) {
  std::string links;
  for (int i = 0; i < 900; ++i) links += "<link name=\"l" + std::to_string(i) + "\"/>";
  const std::string message = Rejection(Sdf(links));
  EXPECT_NE(message.find("/tmp/robot.sdf: too large for libsdformat: its 902 elements (900 <link> elements) would "
                         "take about"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("more than the 850 MB allowed"), std::string::npos) << message;
  std::string worlds = "<?xml version=\"1.0\"?><sdf version=\"1.7\">";
  for (int i = 0; i < 200; ++i) worlds += "<world name=\"w" + std::to_string(i) + "\"/>";
  EXPECT_NE(Rejection(worlds + "</sdf>").find("(200 <world> elements)"), std::string::npos);
}

TEST(SdformatReaderTest, JointKindsPositionsAndLimits) {
  const RobotDescription robot = ReadSdformatFromString(Sdf(R"(
    <pose>0 0 1 0 0 1.5707963267948966</pose>
    <link name="a"><pose>1 0 0 0 0 0</pose></link>
    <link name="b"><pose>2 0 0 0 0 0</pose></link>
    <link name="c"><pose>3 0 0 0 0 0</pose></link>
    <link name="d"><pose>4 0 0 0 0 0</pose></link>
    <link name="e"><pose>5 0 0 0 0 0</pose></link>
    <frame name="tip" attached_to="d"><pose>0.5 0 0 0 0 0</pose></frame>
    <joint name="hinge" type="revolute"><parent>world</parent><child>a</child>
      <axis><xyz>0 1 0</xyz><initial_position>0.25</initial_position>
        <limit><lower>-1</lower><upper>2</upper></limit></axis></joint>
    <joint name="slide" type="prismatic"><parent>a</parent><child>b</child>
      <axis><xyz expressed_in="__model__">1 0 0</xyz><limit><lower>-0.5</lower></limit></axis></joint>
    <joint name="spin" type="continuous"><parent>b</parent><child>c</child>
      <axis><xyz>0 0 1</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis></joint>
    <joint name="ball" type="ball"><pose>0.1 0 0 0 0 0</pose><parent>c</parent><child>d</child></joint>
    <joint name="cross" type="universal"><parent>tip</parent><child>e</child>
      <axis><xyz>1 0 0</xyz></axis><axis2><xyz>0 1 0</xyz></axis2></joint>
    <joint name="huge" type="revolute"><parent>world</parent><child>e</child>
      <axis><xyz>0 0 1</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit></axis></joint>
  )"),
                                                        "/tmp/robot.sdf", {"hinge", "slide"});
  ASSERT_EQ(robot.joints.size(), 6u);
  // The model is turned 90 degrees about z and lifted 1 m: x -> y.
  EXPECT_NEAR((robot.links[0].X_WL.translation() - Eigen::Vector3d(0, 1, 1)).norm(), 0, 1e-15);
  const RobotJoint& hinge = robot.joints[0];
  EXPECT_EQ(hinge.type, RobotJointType::kRevolute);
  EXPECT_EQ(hinge.parent, "world");
  EXPECT_NEAR((hinge.axis_W - Eigen::Vector3d(-1, 0, 0)).norm(), 0, 1e-15);
  EXPECT_EQ(hinge.position, 0.25);
  EXPECT_TRUE(hinge.limited);
  EXPECT_EQ(hinge.lower, -1);
  EXPECT_EQ(hinge.upper, 2);
  const RobotJoint& slide = robot.joints[1];
  EXPECT_EQ(slide.type, RobotJointType::kPrismatic);
  EXPECT_NEAR((slide.axis_W - Eigen::Vector3d(0, 1, 0)).norm(), 0, 1e-15);
  EXPECT_FALSE(slide.limited);  // only <lower> written
  EXPECT_EQ(robot.joints[2].type, RobotJointType::kRevolute);
  EXPECT_FALSE(robot.joints[2].limited);  // continuous: never limited
  const RobotJoint& ball = robot.joints[3];
  EXPECT_EQ(ball.type, RobotJointType::kSpherical);
  EXPECT_NEAR((ball.X_WJ.translation() - Eigen::Vector3d(0, 4.1, 1)).norm(), 0, 1e-15);
  const RobotJoint& cross = robot.joints[4];
  EXPECT_EQ(cross.type, RobotJointType::kUniversal);
  EXPECT_EQ(cross.parent, "d");  // the link the frame `tip` is attached to
  EXPECT_NEAR((cross.axis_W - Eigen::Vector3d(0, 1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((cross.axis2_W - Eigen::Vector3d(-1, 0, 0)).norm(), 0, 1e-15);
  EXPECT_FALSE(robot.joints[5].limited);  // +-1e16: SDFormat's "unlimited"
  EXPECT_EQ(robot.actuated, (std::vector<std::string>{"hinge", "slide"}));
}

TEST(SdformatReaderTest, PlanarBaseAndEndEffectorElement) {
  const RobotDescription robot = ReadSdformatFromString(Sdf(R"(
    <ccma:end_effector link="base" point="0.5 0 0.25" controlled="x y yaw"/>
    <link name="base"><pose>1 2 0 0 0 0</pose></link>
    <joint name="floor" type="planar"><parent>world</parent><child>base</child></joint>
  )"),
                                                        "/tmp/robot.sdf", {});
  ASSERT_EQ(robot.joints.size(), 1u);
  EXPECT_EQ(robot.joints[0].type, RobotJointType::kPlanar);
  EXPECT_NEAR((robot.joints[0].axis_W - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-15);
  EXPECT_NEAR((robot.joints[0].X_WJ.translation() - Eigen::Vector3d(1, 2, 0)).norm(), 0, 1e-15);
  ASSERT_TRUE(robot.has_end_effector);
  EXPECT_EQ(robot.end_effector.link, "base");
  EXPECT_EQ(robot.end_effector.point_L, Eigen::Vector3d(0.5, 0, 0.25));
  EXPECT_EQ(robot.end_effector.controlled, (std::vector<std::string>{"x", "y", "yaw"}));
  const std::string bad_link =
      Rejection(Sdf("<ccma:end_effector link=\"arm\"/><link name=\"a\"/>"));
  EXPECT_NE(bad_link.find("<ccma:end_effector>: link 'arm' is not a link"), std::string::npos)
      << bad_link;
  const std::string bad_point =
      Rejection(Sdf("<ccma:end_effector link=\"a\" point=\"1 2\"/><link name=\"a\"/>"));
  EXPECT_NE(bad_point.find("point: expected 3 finite numbers"), std::string::npos) << bad_point;
  const std::string bad_name =
      Rejection(Sdf("<ccma:end_effector link=\"a\" controlled=\"x yaw x\"/><link name=\"a\"/>"));
  EXPECT_NE(bad_name.find("controlled: 'x' is not one of"), std::string::npos) << bad_name;
}

TEST(SdformatReaderTest, MeshUrisResolveAgainstTheFilesFolder) {
  const fs::path root =
      fs::path(testing::ScratchPath("sdformat_reader", "meshes")).lexically_normal();
  fs::remove_all(root);
  fs::create_directories(root / "robots" / "arm");
  fs::create_directories(root / "gripper" / "meshes");
  std::ofstream(root / "gripper" / "meshes" / "finger.stl") << "solid finger\nendsolid finger\n";
  const std::string path = (root / "robots" / "arm" / "arm.sdf").string();
  std::ofstream(path) << Sdf(R"(
    <link name="a"><pose>1 0 0 0 0 0</pose>
      <visual name="v0"><pose>0 0 0.5 0 0 0</pose>
        <geometry><mesh><uri>model://gripper/meshes/finger.stl</uri><scale>0.001 0.001 0.001</scale></mesh></geometry></visual>
      <visual name="v1"><geometry><mesh><uri>meshes/a.stl</uri></mesh></geometry></visual>
      <visual name="v2"><geometry><mesh><uri>file:///opt/m/b.stl</uri></mesh></geometry></visual>
      <visual name="v3"><geometry><mesh><uri>model://absent/c.stl</uri></mesh></geometry></visual>
      <visual name="v4"><geometry><box><size>1 1 1</size></box></geometry></visual>
    </link>
  )");
  const RobotDescription robot = ReadSdformat(path, {});
  ASSERT_EQ(robot.links.size(), 1u);
  const std::vector<RobotMesh>& meshes = robot.links[0].meshes;
  ASSERT_EQ(meshes.size(), 4u);
  EXPECT_EQ(meshes[0].file, (root / "gripper" / "meshes" / "finger.stl").string());
  EXPECT_NEAR((meshes[0].X_WM.translation() - Eigen::Vector3d(1, 0, 0.5)).norm(), 0, 1e-15);
  EXPECT_EQ(meshes[0].scale, Eigen::Vector3d::Constant(0.001));
  EXPECT_EQ(meshes[1].file, (root / "robots" / "arm" / "meshes" / "a.stl").string());
  EXPECT_EQ(meshes[1].scale, Eigen::Vector3d::Ones());
  EXPECT_EQ(meshes[2].file, "/opt/m/b.stl");
  EXPECT_EQ(meshes[3].file,
            (root / "robots" / "arm" / "c.stl").string());  // not found: the viewer says so
}

TEST(SdformatReaderTest, ModelInsideAWorld) {
  const RobotDescription robot = ReadSdformatFromString(
      "<sdf version=\"1.9\"><world name=\"w\"><model name=\"in world\"><pose>0 0 2 0 0 0</pose>"
      "<link name=\"a\"><pose>1 0 0 0 0 0</pose></link></model></world></sdf>",
      "/tmp/robot.sdf", {});
  EXPECT_EQ(robot.name, "in_world");
  ASSERT_EQ(robot.links.size(), 1u);
  EXPECT_NEAR((robot.links[0].X_WL.translation() - Eigen::Vector3d(1, 0, 2)).norm(), 0, 1e-15);
}

// Freudenstein's equation for a four-bar with ground d, crank a, coupler b,
// rocker c, both angles from the ground line O2 -> O4:
//   K1 cos(theta4) - K2 cos(theta2) + K3 = cos(theta2 - theta4),
//   K1 = d / a, K2 = d / c, K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c).
// Written P cos(theta4) + Q sin(theta4) = R, its two roots are
// atan2(Q, P) +- acos(R / |(P, Q)|); the bundled four-bar (B above the
// ground line) is the '+' root at every crank angle: the roots meet only
// where |A O4| = b +- c, which this crank-rocker (|A O4| in [3, 5]) never
// reaches.
double FreudensteinRocker(double theta2) {
  const double a = 1.0, b = 4.8, c = 2.0, d = 4.0;
  const double k1 = d / a, k2 = d / c, k3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
  const double p = k1 - std::cos(theta2), q = -std::sin(theta2), r = k2 * std::cos(theta2) - k3;
  return std::atan2(q, p) + std::acos(r / std::hypot(p, q));
}

// The angle of a body's x axis (its bar) from world x, about z.
double BarAngle(const State& s, int body) {
  const Eigen::Matrix3d R = s.R_WB(body);
  return std::atan2(R(1, 0), R(0, 0));
}

// The rocker's angle in the file (crank at 90 degrees).
constexpr double kRockerHome = 1.2018068856832935;

double Wrapped(double angle) { return std::remainder(angle, 2 * M_PI); }

TEST(SdformatReaderTest, ImportedFourBarFollowsFreudenstein) {
  ImportOptions options;
  options.actuated = {"crank"};
  options.end_effector_link = "rocker";
  options.end_effector_point_L = Eigen::Vector3d(2, 0, 0);
  const ImportedRobot imported = ImportRobot(ReadSdformat(kFourBar, {"crank"}), options);
  const Model& model = imported.model;
  ASSERT_EQ(model.num_controls(), 1);
  EXPECT_LT(imported.residual_energy, 1e-24);
  const int driver = model.FindBody("driver"), rocker = model.FindBody("rocker");
  ASSERT_GE(driver, 0);
  ASSERT_GE(rocker, 0);
  // The file poses the crank at 90 degrees with every joint at 0: control u
  // turns it to theta2 = pi/2 + u.
  EXPECT_NEAR(model.home_controls()(0), 0, 1e-15);
  const Joint* crank = nullptr;
  const Joint* world_rocker = nullptr;
  for (const Joint& joint : model.joints) {
    if (joint.name == "crank") crank = &joint;
    if (joint.name == "world_rocker") world_rocker = &joint;
  }
  ASSERT_NE(crank, nullptr);
  ASSERT_NE(world_rocker, nullptr);
  ForwardProblem problem(model);
  std::mt19937 random(25);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int i = 0; i < 24; ++i) {
    const double u = angle(random);
    const ForwardResult result = problem.Assemble(Eigen::VectorXd::Constant(1, u));
    ASSERT_TRUE(result.assembled) << "u = " << u;
    EXPECT_FALSE(result.branch_jump) << "u = " << u;
    const double theta2 = BarAngle(problem.state(), driver);
    EXPECT_NEAR(Wrapped(theta2 - (M_PI / 2 + u)), 0, 1e-9) << "u = " << u;
    const double theta4 = BarAngle(problem.state(), rocker);
    EXPECT_NEAR(Wrapped(theta4 - FreudensteinRocker(theta2)), 0, 1e-9) << "theta2 = " << theta2;
    // The reported joint positions are the source's: 0 where the file poses the links.
    EXPECT_NEAR(Wrapped(JointCoordinate(*crank, problem.state()) - u), 0, 1e-9);
    EXPECT_NEAR(Wrapped(JointCoordinate(*world_rocker, problem.state()) - (theta4 - kRockerHome)),
                0, 1e-9);
  }
  // An unknown motor is named with the file (the reader passes the list on).
  options.actuated = {"rocker_motor"};
  try {
    ImportRobot(ReadSdformat(kFourBar, options.actuated), options);
    ADD_FAILURE() << "unknown actuated joint accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("actuated joint 'rocker_motor': no joint of " + kFourBar),
              std::string::npos)
        << e.what();
  }
  // Home itself: the file's rocker angle.
  EXPECT_NEAR(FreudensteinRocker(M_PI / 2), kRockerHome, 1e-12);
}

}  // namespace
}  // namespace ccma
