// Legged bases in URDF and SDFormat (issue 37): a `floating` joint from the
// ground with ccma's extension (<ccma_legged .../>, <ccma:legged .../>,
// formats/internal/legged_extension.h) is a legged base. Export writes it,
// import reads it back with the base's body exactly; a legged agent carrying
// a mast, written by hand in both formats, imports to the closed form of its
// six controls; hostile extensions are refused naming file, line and joint.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "analyses/robot_import.h"
#include "formats/model_loader.h"
#include "formats/sdformat_reader.h"
#include "formats/sdformat_writer.h"
#include "formats/urdf_reader.h"
#include "formats/urdf_writer.h"
#include "problems/control_problem.h"
#include "problems/forward_problem.h"
#include "tests/tool_run.h"

namespace ccma {
namespace legged_export_test {

const std::vector<std::string> kLeggedModels = {"6dof_three_legged", "4dof_two_legged"};

// Writes `text` to a scratch file `name` and returns its path.
std::string Scratch(const std::string& name, const std::string& text) {
  const std::string path = testing::ScratchPath("legged_export", name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

Model ImportUrdfText(const std::string& name, const UrdfExport& e, const ImportOptions& options = {}) {
  const std::string path = Scratch(name + ".urdf", e.urdf);
  Scratch(name + ".closures.yaml", e.closures);
  return ImportRobot(ReadUrdf(path, ClosureFilePath(path)), options).model;
}

Model ImportSdfText(const std::string& name, const std::string& text, const ImportOptions& options = {}) {
  return ImportRobot(ReadSdformat(Scratch(name + ".sdf", text), {}), options).model;
}

void ExpectSameRange(const ControlRange& a, const ControlRange& b, const std::string& what) {
  EXPECT_EQ(a.limited, b.limited) << what;
  EXPECT_EQ(a.lower, b.lower) << what;
  EXPECT_EQ(a.upper, b.upper) << what;
}

// Every base of `imported` is the original's legged base with its body
// (height, limits, footprint) to the last bit, in the same control order.
void ExpectSameLeggedBases(const Model& original, const Model& imported, const std::string& what) {
  ASSERT_EQ(imported.num_bases(), original.num_bases()) << what;
  ASSERT_EQ(imported.num_controls(), original.num_controls()) << what;
  for (int k = 0; k < original.num_bases(); ++k) {
    const MobileBase &a = original.mobile_bases[k], &b = imported.mobile_bases[k];
    EXPECT_EQ(b.name, a.name) << what;
    ASSERT_EQ(b.type, BaseType::kLegged) << what << " " << a.name;
    EXPECT_EQ(b.legged.height, a.legged.height) << what;
    ExpectSameRange(a.legged.height_limits, b.legged.height_limits, what + " height");
    ExpectSameRange(a.legged.roll_limits, b.legged.roll_limits, what + " roll");
    ExpectSameRange(a.legged.pitch_limits, b.legged.pitch_limits, what + " pitch");
    EXPECT_EQ(b.legged.footprint, a.legged.footprint) << what;
    EXPECT_LT((imported.bodies[b.body].p_WB_home - original.bodies[a.body].p_WB_home).norm(), 1e-12) << what;
  }
}

// Controls near home that move the bodies' height, roll and pitch too: the
// original's controller driven to end-effector targets near home (a CCMA's
// bases are tied together by the chain, so most nearby controls do not
// assemble). The imported model puts the end-effector at the same pose there.
void ExpectSamePoseAtMovedControls(const Model& original, const Model& imported, const std::string& what) {
  const EndEffectorPose home = ComputeEndEffectorPose(original, State::Home(original));
  for (const double step : {0.0, 0.02, -0.03}) {
    ControlProblem control(original);
    PoseTarget target;
    target.position = home.position + step * Eigen::Vector3d(1.0, -0.5, 0.7);
    target.rpy = home.rpy + step * Eigen::Vector3d(0.4, -0.6, 1.0);
    ASSERT_TRUE(control.MoveTo(target).assembled) << what << " step " << step;
    const Eigen::VectorXd u = control.controls();
    ForwardProblem a(original), b(imported);
    ASSERT_TRUE(a.Assemble(u).assembled) << what << " step " << step;
    ASSERT_TRUE(b.Assemble(u).assembled) << what << " step " << step;
    EXPECT_LT((a.end_effector().position - b.end_effector().position).norm(), 1e-9) << what << " step " << step;
    EXPECT_LT((a.end_effector().rotation - b.end_effector().rotation).norm(), 1e-9) << what << " step " << step;
  }
}

TEST(LeggedExport, BundledLeggedModelsComeBackWithTheirBodiesThroughUrdfAndSdformat) {
  for (const std::string& name : kLeggedModels) {
    const Model model = LoadModel(testing::ModelPath(name));
    const UrdfExport urdf = WriteUrdf(model);
    EXPECT_NE(urdf.urdf.find("type=\"floating\""), std::string::npos);
    EXPECT_NE(urdf.urdf.find("<ccma_legged body_height=\"0.45\""), std::string::npos);
    EXPECT_NE(urdf.closures.find("name_mot: ['dog0_floating', 'dog1_floating'"), std::string::npos) << urdf.closures;
    const Model from_urdf = ImportUrdfText(name, urdf);
    ExpectSameLeggedBases(model, from_urdf, name + " (urdf)");
    ExpectSamePoseAtMovedControls(model, from_urdf, name + " (urdf)");
    const Model from_sdf = ImportSdfText(name, WriteSdformat(model).sdf);
    ExpectSameLeggedBases(model, from_sdf, name + " (sdf)");
    ExpectSamePoseAtMovedControls(model, from_sdf, name + " (sdf)");
  }
}

// A legged agent carrying a mast, by hand: body frame at (1, 2, 0.45),
// heading 0.5; the mast welded 0.1 m ahead and 0.3 m up, its tip 0.5 m
// higher. EXT stands for the joint's extension element.
constexpr char kDogUrdf[] = R"(<?xml version="1.0"?>
<robot name="dog_mast">
  <link name="world"/>
  <link name="dog"/>
  <link name="mast"/>
  <joint name="stand" type="floating">
    <parent link="world"/><child link="dog"/>
    <origin xyz="1 2 0.45" rpy="0 0 0.5"/>
    EXT
  </joint>
  <joint name="weld" type="fixed">
    <parent link="dog"/><child link="mast"/>
    <origin xyz="0.1 0 0.3" rpy="0 0 0"/>
  </joint>
</robot>
)";

constexpr char kDogSdf[] = R"(<?xml version="1.0"?>
<sdf version="1.7" xmlns:ccma="https://ccma.dev/sdf">
  <model name="dog_mast">
    <link name="dog"><pose>1 2 0.45 0 0 0.5</pose></link>
    <link name="mast"><pose relative_to="dog">0.1 0 0.3 0 0 0</pose></link>
    <joint name="stand" type="floating">
      <parent>world</parent><child>dog</child>
      EXT
    </joint>
    <joint name="weld" type="fixed"><parent>dog</parent><child>mast</child></joint>
  </model>
</sdf>
)";

constexpr char kDogExtension[] =
    R"(body_height="0.45" height_limits="0.3 0.55" roll_limits="-0.25 0.25" pitch_limits="-0.2 0.2" footprint="0.7 0.3")";

std::string WithExtension(const std::string& text, const std::string& extension) {
  std::string out = text;
  return out.replace(out.find("EXT"), 3, extension);
}

ImportOptions MastTip() {
  ImportOptions options;
  options.end_effector_link = "mast";
  options.end_effector_point_L = Eigen::Vector3d(0, 0, 0.5);
  return options;
}

// The mast tip at controls (x, y, heading, height, roll, pitch): the body
// frame at (x, y, height) turned by Rz(heading) Ry(pitch) Rx(roll).
Eigen::Vector3d MastTipAt(const Eigen::VectorXd& u) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(u[2], Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(u[5], Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(u[4], Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return Eigen::Vector3d(u[0], u[1], u[3]) + R * Eigen::Vector3d(0.1, 0, 0.8);
}

void ExpectMastClosedForm(const Model& model, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(model.num_bases(), 1);
  const MobileBase& base = model.mobile_bases[0];
  ASSERT_EQ(base.type, BaseType::kLegged);
  EXPECT_EQ(base.name, "dog");
  EXPECT_EQ(base.legged.height, 0.45);
  EXPECT_EQ(base.legged.height_limits.lower, 0.3);
  EXPECT_EQ(base.legged.pitch_limits.upper, 0.2);
  EXPECT_EQ(base.legged.footprint, Eigen::Vector2d(0.7, 0.3));
  Eigen::VectorXd home(6);
  home << 1, 2, 0.5, 0.45, 0, 0;
  ASSERT_EQ(model.num_controls(), 6);
  EXPECT_LT((model.home_controls() - home).norm(), 1e-15);
  Eigen::VectorXd u(6);
  u << 1.2, 1.9, 0.8, 0.5, 0.2, -0.15;
  ForwardProblem forward(model);
  ASSERT_TRUE(forward.Assemble(u).assembled);
  EXPECT_LT((forward.end_effector().position - MastTipAt(u)).norm(), 1e-9);
}

TEST(LeggedImport, AFloatingJointWithTheExtensionIsALeggedBaseAtItsBodyPose) {
  ExpectMastClosedForm(
      ImportRobot(ReadUrdfFromString(WithExtension(kDogUrdf, std::string("<ccma_legged ") + kDogExtension + "/>"),
                                     Scratch("dog.urdf", "")),
                  MastTip())
          .model,
      "urdf");
  ExpectMastClosedForm(
      ImportSdfText("dog", WithExtension(kDogSdf, std::string("<ccma:legged ") + kDogExtension + "/>"), MastTip()),
      "sdf");
}

// `text` (URDF or SDFormat, chosen by `sdf`) imported: refused with a
// ModelError containing `needle`.
void ExpectRefused(bool sdf, const std::string& text, const std::string& needle) {
  try {
    if (sdf) {
      ImportRobot(ReadSdformatFromString(text, "dog.sdf", {}), MastTip());
    } else {
      ImportRobot(ReadUrdfFromString(text, "dog.urdf"), MastTip());
    }
    ADD_FAILURE() << "accepted; expected: " << needle;
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(LeggedImport, HostileExtensionsAreRefusedNamingFileLineJointAndAttribute) {
  struct Case {
    std::string attributes, needle;
  };
  const std::vector<Case> cases = {
      {R"(body_height="nan")", "body_height: expected 1 finite number within 1e4, got 'nan'"},
      {R"(body_height="1e300")", "body_height: expected 1 finite number within 1e4"},
      {R"(body_height="0.45 0.3")", "body_height: expected 1 finite number"},
      {R"(body_height="0.45m")", "body_height: expected 1 finite number"},
      {R"(body_height="-0.45")", "body_height: must be > 0 m"},
      {R"(height_limits="0.3 0.55")", "body_height is required"},
      {R"(body_height="0.45" height_limits="0.5 0.6")", "height_limits: must contain the home value 0.45 m"},
      {R"(body_height="0.45" roll_limits="0.1 0.2")", "roll_limits: must contain the home value 0 rad"},
      {R"(body_height="0.45" pitch_limits="-0.1")", "pitch_limits: expected 2 finite numbers"},
      {R"(body_height="0.45" footprint="0.7 0")", "footprint: both sides must be > 0 m"},
      {R"(body_height="0.45" footprint="0.7 0.3 0.1")", "footprint: expected 2 finite numbers"},
      {R"(body_height="0.45" colour="red")", "unknown attribute 'colour'"},
  };
  for (const Case& c : cases) {
    ExpectRefused(false, WithExtension(kDogUrdf, "<ccma_legged " + c.attributes + "/>"),
                  "dog.urdf:9: joint 'stand': <ccma_legged>: " + c.needle);
    ExpectRefused(true, WithExtension(kDogSdf, "<ccma:legged " + c.attributes + "/>"),
                  "dog.sdf:6: joint 'stand': <ccma:legged>: " + c.needle);  // libsdformat: the joint's line
  }
  // The link's frame at home is the body frame: at body_height, upright.
  const std::string upright = "joint 'stand': the legged base link 'dog' must be upright at home with its frame at "
                              "body_height 0.5 m above the ground (it is at 0.45 m)";
  ExpectRefused(false, WithExtension(kDogUrdf, R"(<ccma_legged body_height="0.5"/>)"), "dog.urdf:6: " + upright);
  ExpectRefused(true, WithExtension(kDogSdf, R"(<ccma:legged body_height="0.5"/>)"), "dog.sdf:6: " + upright);
  std::string tilted = WithExtension(kDogUrdf, R"(<ccma_legged body_height="0.45"/>)");
  tilted.replace(tilted.find("rpy=\"0 0 0.5\""), 13, "rpy=\"0.1 0 0.5\"");
  ExpectRefused(false, tilted, "dog.urdf:6: joint 'stand': the legged base link 'dog' must be upright");
}

TEST(LeggedImport, AFloatingJointNeedsTheExtensionAndTheGround) {
  ExpectRefused(false, WithExtension(kDogUrdf, ""),
                "dog.urdf:6: joint 'stand': a floating joint from the ground is a legged base and needs ccma's "
                "<ccma_legged> element");
  ExpectRefused(true, WithExtension(kDogSdf, ""),
                "dog.sdf:6: joint 'stand': a floating joint from world is a legged base and needs ccma's "
                "<ccma:legged> element");
  const std::string twice = std::string("<ccma_legged ") + kDogExtension + "/><ccma_legged body_height=\"1\"/>";
  ExpectRefused(false, WithExtension(kDogUrdf, twice), "dog.urdf:9: joint 'stand': more than one <ccma_legged>");
  // On another joint the extension is a mistake, not ignored.
  std::string on_weld = WithExtension(kDogUrdf, std::string("<ccma_legged ") + kDogExtension + "/>");
  on_weld.replace(on_weld.find("<origin xyz=\"0.1"), 0, "<ccma_legged body_height=\"0.45\"/>");
  ExpectRefused(false, on_weld, "joint 'weld': <ccma_legged> belongs in a floating joint from the ground");
  // A floating joint between two links is no base: ccma has no free-flying body.
  std::string between = WithExtension(kDogUrdf, std::string("<ccma_legged ") + kDogExtension + "/>");
  between.replace(between.find("\"weld\" type=\"fixed\""), 19, "\"weld\" type=\"floating\"");
  ExpectRefused(false, between, "dog.urdf:11: joint 'weld': joint type not supported");
}

// issue 49: ccma's SDFormat elements are those of its namespace URI, not of
// the prefix `ccma`. Another prefix bound to https://ccma.dev/sdf (on <sdf>,
// on the joint, on the element itself) is ccma's; `ccma:` bound to another
// URI, rebound below <sdf>, or never declared is another vocabulary's.
TEST(LeggedImport, TheExtensionIsMatchedByItsNamespaceUriNotItsPrefix) {
  const std::string ccma_ns = "xmlns:ccma=\"https://ccma.dev/sdf\"";
  auto with = [&](const std::string& root_ns, const std::string& element) {
    std::string text = WithExtension(kDogSdf, element);
    return text.replace(text.find(ccma_ns), ccma_ns.size(), root_ns);
  };
  const std::string ext = std::string(" ") + kDogExtension + "/>";
  ExpectMastClosedForm(ImportSdfText("c", with("xmlns:c=\"https://ccma.dev/sdf\"", "<c:legged" + ext), MastTip()),
                       "another prefix on <sdf>");
  ExpectMastClosedForm(ImportSdfText("own", with("", "<k:legged xmlns:k=\"https://ccma.dev/sdf\"" + ext), MastTip()),
                       "declared on the element");
  std::string on_joint = with("", "<j:legged" + ext);
  on_joint.replace(on_joint.find("type=\"floating\""), 0, "xmlns:j=\"https://ccma.dev/sdf\" ");
  ExpectMastClosedForm(ImportSdfText("joint", on_joint, MastTip()), "declared on the joint");
  const std::string needs = "dog.sdf:6: joint 'stand': a floating joint from world is a legged base and needs "
                            "ccma's <ccma:legged> element (body_height=\"m\", docs/import.md) ('<ccma:legged>' here ";
  ExpectRefused(true, with("xmlns:ccma=\"https://elsewhere.example/robots\"", "<ccma:legged" + ext),
                needs + "is bound to 'https://elsewhere.example/robots', not https://ccma.dev/sdf)");
  ExpectRefused(true, with("", "<ccma:legged" + ext),
                needs + "has an undeclared prefix: declare xmlns:ccma=\"https://ccma.dev/sdf\")");
  std::string rebound = WithExtension(kDogSdf, "<ccma:legged" + ext);
  rebound.replace(rebound.find("<model name"), 6, "<model xmlns:ccma=\"https://elsewhere.example/robots\"");
  ExpectRefused(true, rebound, needs + "is bound to 'https://elsewhere.example/robots'");
  // Another vocabulary's <x:legged> on a fixed joint is ignored, as libsdformat ignores it.
  std::string foreign = WithExtension(kDogSdf, "<ccma:legged" + ext);
  foreign.replace(foreign.find("<parent>dog</parent>"), 0, "<o:legged xmlns:o=\"https://other.example\" a=\"1\"/>");
  ExpectMastClosedForm(ImportSdfText("foreign", foreign, MastTip()), "another vocabulary's element elsewhere");
}

// issue 49: the extension's numbers are decimal (strtod would read the hex
// float 0x1.cccccccccccccp-2 as 0.45), and the element takes attributes
// only: a child element or text inside is refused, naming file, line, joint
// and element.
TEST(LeggedImport, HexFloatsAndContentInsideTheExtensionAreRefused) {
  for (const std::string hex : {"0x1.cccccccccccccp-2", "0X1P-1", "0x0.7333333333333p0"}) {
    ExpectRefused(false, WithExtension(kDogUrdf, "<ccma_legged body_height=\"" + hex + "\"/>"),
                  "dog.urdf:9: joint 'stand': <ccma_legged>: body_height: expected 1 finite number within 1e4, got '" +
                      hex + "'");
    ExpectRefused(true, WithExtension(kDogSdf, "<ccma:legged body_height=\"0.45\" footprint=\"" + hex + " 0.3\"/>"),
                  "dog.sdf:6: joint 'stand': <ccma:legged>: footprint: expected 2 finite numbers within 1e4, got '" +
                      hex + " 0.3'");
  }
  const std::string open = std::string("<ccma_legged ") + kDogExtension + ">";
  ExpectRefused(false, WithExtension(kDogUrdf, open + "\n<leg name=\"front\"/></ccma_legged>"),
                "dog.urdf:9: joint 'stand': <ccma_legged>: a child element '<leg>' (line 10): the element takes "
                "attributes only");
  ExpectRefused(false, WithExtension(kDogUrdf, open + "0.5</ccma_legged>"),
                "dog.urdf:9: joint 'stand': <ccma_legged>: text '0.5' inside: the element takes attributes only");
  const std::string sdf_open = std::string("<ccma:legged ") + kDogExtension + ">";
  ExpectRefused(true, WithExtension(kDogSdf, sdf_open + "<leg name=\"front\"/></ccma:legged>"),
                "dog.sdf:6: joint 'stand': <ccma:legged>: a child element '<leg>': the element takes attributes only");
  ExpectRefused(true, WithExtension(kDogSdf, sdf_open + "0.5</ccma:legged>"),
                "dog.sdf:6: joint 'stand': <ccma:legged>: text '0.5' inside: the element takes attributes only");
  // Comments and white space inside are no content.
  ExpectMastClosedForm(
      ImportRobot(ReadUrdfFromString(WithExtension(kDogUrdf, open + "\n  <!-- a note -->\n</ccma_legged>"),
                                     Scratch("commented.urdf", "")),
                  MastTip())
          .model,
      "a comment inside");
}

// The command line: a legged model exports (both formats) and imports
// back; a floating joint without the extension exits 2 with one line.
TEST(LeggedExportCommand, ExportsLeggedModelsAndRefusesAFloatingJointWithoutTheExtension) {
  const std::string model_path = testing::ModelPath("4dof_two_legged");
  for (const std::string format : {"urdf", "sdf"}) {
    const std::string out = testing::ScratchPath("legged_export_cli", "two_legged." + format);
    const testing::ToolRun run = testing::RunTool({"export", "--model=" + model_path, "--format=" + format, "--out=" + out});
    ASSERT_EQ(run.status, 0) << run.err;
    const Model model = LoadModel(model_path);
    EXPECT_EQ(testing::Slurp(out), format == "urdf" ? WriteUrdf(model).urdf : WriteSdformat(model).sdf);
    const std::string yaml = testing::ScratchPath("legged_export_cli", "again_" + format + ".yaml");
    std::vector<std::string> import = {"import", "--from=" + out, "--out=" + yaml};
    if (format == "urdf") import.push_back("--closures=" + ClosureFilePath(out));
    const testing::ToolRun again = testing::RunTool(import);
    ASSERT_EQ(again.status, 0) << again.err;
    ExpectSameLeggedBases(model, LoadModel(yaml), format);
  }
  const std::string bare = Scratch("bare.urdf", WithExtension(kDogUrdf, ""));
  const testing::ToolRun run = testing::RunTool({"import", "--from=" + bare, "--end_effector=mast",
                                                 "--out=" + testing::ScratchPath("legged_export_cli", "bare.yaml")});
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_NE(run.err.find(bare + ":6: joint 'stand': a floating joint from the ground"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

}  // namespace
}  // namespace ccma
