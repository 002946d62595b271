// `ccma workspace`, `ccma design`, `ccma simulate`, `ccma control`,
// `ccma trajectory`, `ccma replay` and `ccma bench` bound their work by its estimated cost
// (issue 49 items 11 and 12; docs/security.md, "Work bounded by its cost"):
// a run estimated beyond --max_minutes (default 10) is refused within
// seconds, status 2, naming the estimate and the --max_minutes that would
// allow it, nothing written. They used to run on in silence: a million
// samples of a bundled model for 278 s, a thousand design iterations for
// some 28 minutes. The estimate's words and timing on a set clock:
// work_estimate_test.cc.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "tests/tool_run.h"

namespace ccma {
namespace work_bound_cli_test {

namespace fs = std::filesystem;
using testing::ModelPath;
using testing::RunTool;
using testing::ToolRun;

std::string Scratch(const std::string& name) { return testing::ScratchPath("work_bound", name); }

// `ccma generate --agents=N` made compliant (16 KB at 24 agents): a mass of
// 1 kg on every body, springs on every base and spherical joint.
std::string CompliantModel(int agents) {
  const std::string plain = Scratch("plain.yaml"), compliant = Scratch("compliant.yaml");
  const ToolRun r = RunTool({"generate", "--agents=" + std::to_string(agents), "--out=" + plain});
  EXPECT_EQ(r.status, 0) << r.err;
  std::string text = testing::Slurp(plain);
  text = std::regex_replace(text, std::regex(R"((- \{name: \w+, position: \[[^\]]*\])\})"), "$1, mass: 1}");
  text = std::regex_replace(text, std::regex(R"((pose: \[[^\]]*\])\})"), "$1, stiffness: [1.0e5, 1.0e5, 1.0e3]}");
  text = std::regex_replace(text, std::regex(R"(- \{type: spherical, )"),
                            "- {type: spherical, stiffness: {translation: 1.0e7}, ");
  std::ofstream(compliant) << text;
  return compliant;
}

// The refusal: status 2, nothing on stdout, no output file, and the words.
void ExpectRefused(const ToolRun& r, const std::string& command, const std::string& work, const std::string& out) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_NE(r.err.find("ccma " + command + ": about "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(work), std::string::npos) << r.err;
  // The advice: a bound that runs it, or (a sanitized build's estimates are
  // many times longer) less work when that would exceed a week.
  EXPECT_TRUE(std::regex_search(
      r.err, std::regex("allows: (give --max_minutes=[0-9]+ or more to run it|ask for less work \\(the bound is at "
                        "most a week\\))")))
      << r.err;
}

// trajectory --compensate: a 60-byte waypoint file whose path takes 50,000
// steps of 2 micrometres on a compliant Stewart-Gough platform (half a
// millisecond each, half a minute in all) is refused at a bound of 1.2 s;
// it used to run on in silence.
TEST(WorkBound, ALongCompensatedPathIsRefused) {
  const std::string model = std::string(CCMA_SOURCE_DIR) + "/examples/statics/stewart_gough_compliant.yaml";
  const std::string path = Scratch("long_path.csv"), out = Scratch("long_path_rows.csv");
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n10,0.1,0,0.5,0,0,0\n";
  const ToolRun r = RunTool({"trajectory", "--model=" + model, "--waypoints=" + path, "--out=" + out, "--compensate",
                       "--max_step_m=0.000002", "--max_minutes=0.02"},
                      60);
  ExpectRefused(r, "trajectory", "compensated path steps (", out);
}

// simulate: one base driven 1,900 m away tears the chain at once; the
// 95,000 sub-steps that follow (a quarter of a minute) are refused at a
// bound of 0.6 s.
TEST(WorkBound, AFarTornWalkIsRefused) {
  const std::string far =
      "1900.499271447,0.418938487,0.698131701,-0.499271447,0.418938487,2.443460953,-0.612447096,0.222912513,"
      "2.792526803,-0.113175649,-0.641851,-1.745329252,0.113175649,-0.641851,-1.396263402,0.612447096,"
      "0.222912513,0.34906585";
  const ToolRun r =
      RunTool({"simulate", "--model=" + ModelPath("6dof_six_agents"), "--controls=" + far, "--max_minutes=0.01"}, 60);
  ExpectRefused(r, "simulate", "assembly sub-steps (", Scratch("no_such_output"));
}

// bench: 10,000 steps of a bundled model (about a minute) are refused at a
// bound of 0.6 s, and the --out folder it made is gone again.
TEST(WorkBound, ALongBenchIsRefused) {
  const std::string out = Scratch("bench_out");
  fs::remove_all(out);
  const ToolRun r = RunTool({"bench", "--model=" + ModelPath("6dof_six_agents"), "--steps=10000", "--out=" + out,
                             "--max_minutes=0.01"},
                            60);
  ExpectRefused(r, "bench", "control steps (", out);
}

// control: a 0.1 m move in steps of 2 micrometres (50,000 path steps, some
// tens of seconds) is refused at a bound of 0.6 s; it used to run on in
// silence (a 1000-agent model's long move for hours).
TEST(WorkBound, ALongControlMoveIsRefused) {
  const ToolRun r = RunTool({"control", "--model=" + ModelPath("6dof_six_agents"), "--target=0.1,0,0.6,0,0,0",
                             "--max_step_m=0.000002", "--max_minutes=0.01"},
                            60);
  ExpectRefused(r, "control", "path steps (", Scratch("no_such_output"));
}

// replay: a 2,000 s stay at home on 6dof_six_agents is 40,000 chain solves
// at 20 Hz, refused at a bound of a hundredth of a minute.
TEST(WorkBound, ALongReplayIsRefused) {
  const std::string path = Scratch("stay.csv"), out = Scratch("stay_replay");
  std::ofstream(path) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n2000,0,0,0.6,0,0,0\n";
  const ToolRun r = RunTool({"replay", "--model=" + ModelPath("6dof_six_agents"), "--waypoints=" + path,
                             "--out=" + out, "--max_minutes=0.01"},
                            60);
  ExpectRefused(r, "replay", "chain solves (", out);
}

TEST(WorkBound, AMillionSampleMapBeyondTheBoundIsRefusedInSeconds) {
  // 4dof_reduced: a sample costs a fraction of a millisecond, a million of
  // them minutes; half a minute is allowed.
  const std::string out = Scratch("million.csv");
  const ToolRun r = RunTool({"workspace", "--model=" + ModelPath("4dof_reduced"), "--x=-0.5:0.5", "--z=0.4:1.0",
                             "--resolution=1000", "--max_minutes=0.5", "--out=" + out},
                            60);
  ExpectRefused(r, "workspace", "for 1,000,000 samples (", out);
}

TEST(WorkBound, TheDefaultBoundRefusesAMapOfHours) {
  // A million samples of a 24-agent compliant model: each row's stiffness
  // column alone is a compliance solve (a tenth of a second), hours in all.
  const std::string out = Scratch("hours.csv");
  const ToolRun r = RunTool({"workspace", "--model=" + CompliantModel(24), "--x=-0.1:0.1", "--z=0.5:0.7",
                             "--resolution=1000", "--out=" + out},
                            60);
  ExpectRefused(r, "workspace", "for 1,000,000 samples (", out);
  EXPECT_NE(r.err.find("10 min that --max_minutes=10 allows"), std::string::npos) << r.err;
}

TEST(WorkBound, AThousandIterationsOfTheDeflectionObjectiveAreRefused) {
  // Each iteration of the objective re-solves the targets and the compliance:
  // about a second; a thousand of them are minutes beyond one.
  const std::string targets = Scratch("targets.csv"), out = Scratch("designed.yaml");
  std::ofstream(targets) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n1,0.02,0.01,0.61,0,0,0\n";
  const ToolRun r = RunTool({"design", "--model=" + CompliantModel(24), "--targets=" + targets, "--out=" + out,
                             "--objective=deflection", "--vary=joint2.point,joint5.point,joint8.point",
                             "--max_change=0.1", "--design_iterations=1000", "--max_minutes=1"},
                            120);
  ExpectRefused(r, "design", "for up to 1,000 design iterations of the deflection objective (", out);
}

TEST(WorkBound, TheBoundIsAFlagWithARange) {
  for (const std::string bad : {"0", "-1", "10081", "nan"}) {
    const ToolRun r = RunTool({"workspace", "--model=" + ModelPath("4dof_reduced"), "--z=0.5:0.7",
                               "--max_minutes=" + bad, "--out=" + Scratch("bad.csv")});
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--max_minutes"), std::string::npos) << r.err;
  }
  // Within the bound nothing changes: no word on stderr for a short map.
  const ToolRun ok = RunTool({"workspace", "--model=" + ModelPath("4dof_reduced"), "--z=0.5:0.7", "--resolution=5",
                              "--max_minutes=0.1", "--out=" + Scratch("ok.csv")});
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(ok.err, "");
}

}  // namespace work_bound_cli_test
}  // namespace ccma
