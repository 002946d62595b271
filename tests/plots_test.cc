// apps/plots.h: gnuplot started without a shell, strings quoted so that no
// input can run a command, and the replay's plots and report.
#include "apps/plots.h"
#include "tests/tool_run.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ccma::cli {
namespace plots_test {

using documents::ReplayRmseTable;
using documents::ReportedComponents;
using documents::WriteReplayCsv;

namespace fs = std::filesystem;

const char kHostile[] = "'.system('touch PWNED').'";

std::string Slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh, empty folder per test.
fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(ccma::testing::TestDir()) / ("plots_test_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

#define SKIP_WITHOUT_GNUPLOT()                                                               \
  if (FindGnuplot().empty()) GTEST_SKIP() << "gnuplot is not installed (not on PATH): "      \
                                             "install gnuplot-nox to run this test"

TEST(GnuplotQuote, PlainTextIsSingleQuotedUnchanged) {
  EXPECT_EQ(GnuplotQuote("abc"), "'abc'");
  EXPECT_EQ(GnuplotQuote(""), "''");
  // Backquotes, @macros, backslashes and double quotes mean nothing in single quotes.
  EXPECT_EQ(GnuplotQuote("`touch X` @m \\ \"q\""), "'`touch X` @m \\ \"q\"'");
  EXPECT_EQ(GnuplotQuote("Gr\xc3\xbc\xc3\x9f" "e \xe2\x9c\x93"), "'Gr\xc3\xbc\xc3\x9f" "e \xe2\x9c\x93'");
}

TEST(GnuplotQuote, QuotesAreSplicedInAsDoubleQuotedStrings) {
  EXPECT_EQ(GnuplotQuote("it's"), "('it'.\"'\".'s')");
  EXPECT_EQ(GnuplotQuote("'"), "(\"'\")");
  EXPECT_EQ(GnuplotQuote("''"), "(\"'\".\"'\")");
  EXPECT_EQ(GnuplotQuote(kHostile), "(\"'\".'.system('.\"'\".'touch PWNED'.\"'\".').'.\"'\")");
}

TEST(GnuplotQuote, ControlCharactersCannotEndTheCommand) {
  EXPECT_EQ(GnuplotQuote("a\nb\rc\td"), "'a?b?c?d'");
  EXPECT_EQ(GnuplotQuote(std::string("x\0y\x7f", 4)), "'x?y?'");
  EXPECT_EQ(GnuplotQuote("a'\nsystem('touch X')\n'"),
            "('a'.\"'\".'?system('.\"'\".'touch X'.\"'\".')?'.\"'\")");
}

// Outside the single-quoted runs there is only "'", '.', '(' and ')'.
TEST(GnuplotQuote, NothingButQuotesEverLeavesASingleQuotedRun) {
  for (const std::string text : {std::string(kHostile), std::string("'''"), std::string("a'b''c'''d"),
                                 std::string("\n'\n"), std::string("'`id`'"), std::string("\"'\"")}) {
    const std::string q = GnuplotQuote(text);
    bool inside = false;
    for (size_t i = 0; i < q.size(); ++i) {
      EXPECT_GE(static_cast<unsigned char>(q[i]), 0x20) << text;
      if (q[i] == '\'') {
        inside = !inside;
      } else if (!inside) {
        if (q.compare(i, 3, "\"'\"") == 0) {
          i += 2;
        } else {
          EXPECT_NE(std::string("().").find(q[i]), std::string::npos) << text << " -> " << q << " at " << i;
        }
      }
    }
    EXPECT_FALSE(inside) << q;
  }
}

TEST(RunGnuplot, RunsAScriptInTheWorkingDirectory) {
  SKIP_WITHOUT_GNUPLOT();
  const fs::path dir = FreshDir("run");
  const std::string error = RunGnuplot("set print 'made_by_gnuplot.txt'\nprint 'hello'\n", dir.string());
  EXPECT_EQ(error, "");
  EXPECT_EQ(Slurp(dir / "made_by_gnuplot.txt"), "hello\n");
}

TEST(RunGnuplot, QuotedStringsComeBackUnchanged) {
  SKIP_WITHOUT_GNUPLOT();
  const fs::path dir = FreshDir("roundtrip");
  for (const std::string text :
       {std::string(kHostile), std::string("`touch PWNED` @x \\U+00E9"), std::string("it's \"quoted\" \\n"),
        std::string("Gr\xc3\xbc\xc3\x9f" "e"), std::string("'''a''''b'"), std::string("'"), std::string("\"'\"")}) {
    ASSERT_EQ(RunGnuplot("set print 'printed.txt'\nprint " + GnuplotQuote(text) + "\n", dir.string()), "") << text;
    EXPECT_EQ(Slurp(dir / "printed.txt"), text + "\n");
  }
  EXPECT_FALSE(fs::exists(dir / "PWNED"));
}

TEST(RunGnuplot, AHostileTitleRunsNoCommandButNaiveQuotingWould) {
  SKIP_WITHOUT_GNUPLOT();
  const std::string plot = "set terminal svg\nset output 'plot.svg'\nplot sin(x)\n";
  const fs::path safe = FreshDir("safe");
  EXPECT_EQ(RunGnuplot("set title " + GnuplotQuote(kHostile) + "\nset xlabel " + GnuplotQuote("`touch PWNED`") +
                           "\n" + plot,
                       safe.string()),
            "");
  EXPECT_TRUE(fs::exists(safe / "plot.svg"));
  EXPECT_FALSE(fs::exists(safe / "PWNED")) << "a quoted title ran a command";
  // The control: the same title pasted between quotes does run `touch`, so
  // the check above can see the attack.
  const fs::path naive = FreshDir("naive");
  RunGnuplot(std::string("set title '") + kHostile + "'\n" + plot, naive.string());
  EXPECT_TRUE(fs::exists(naive / "PWNED")) << "the attack did not work: this test cannot detect it";
}

TEST(RunGnuplot, FailuresAreReturnedNotThrown) {
  SKIP_WITHOUT_GNUPLOT();
  const fs::path dir = FreshDir("fail");
  const std::string syntax = RunGnuplot("plot sin(x) nonsense_token\n", dir.string());
  EXPECT_NE(syntax.find("exited with status"), std::string::npos) << syntax;
  const std::string missing = RunGnuplot("print 1\n", (dir / "does_not_exist").string());
  EXPECT_NE(missing.find("cannot start"), std::string::npos) << missing;
  // A script that ends gnuplot before it is fully written (a broken pipe).
  std::string long_script = "exit\n";
  for (int i = 0; i < 20000; ++i) long_script += "print 'padding the script beyond a pipe buffer'\n";
  // Writing to it must neither kill this process (SIGPIPE) nor pass unnoticed.
  const std::string broken = RunGnuplot(long_script, dir.string());
  EXPECT_NE(broken.find("writing the script to gnuplot failed"), std::string::npos) << broken;
}

TEST(RunGnuplot, GnuplotNotOnThePathIsReported) {
  const char* old = std::getenv("PATH");
  const std::string saved = old != nullptr ? old : "";
  setenv("PATH", "/nonexistent_dir_for_ccma_test", 1);
  const std::string found = FindGnuplot();
  const std::string error = RunGnuplot("print 1\n", ccma::testing::TestDir());
  setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(found, "");
  EXPECT_NE(error.find("gnuplot not found"), std::string::npos) << error;
}

TEST(DistinctColour, GivesDifferentColoursToManyBases) {
  std::vector<std::string> colours;
  for (int i = 0; i < 48; ++i) colours.push_back(DistinctColour(i, 48));
  for (int i = 0; i < 48; ++i) {
    EXPECT_EQ(colours[i].size(), 7u);
    for (int j = 0; j < i; ++j) EXPECT_NE(colours[i], colours[j]) << i << " " << j;
  }
}

// A model built in code with hostile names (the loader would refuse them;
// the plotting code must be safe on its own).
Model HostileModel(int bases, bool paper_components) {
  Model m;
  m.name = std::string("model") + kHostile;
  for (int k = 0; k < bases; ++k) {
    MobileBase b;
    b.name = "b" + std::to_string(k) + kHostile + "\n`touch PWNED`";
    m.mobile_bases.push_back(b);
  }
  m.end_effector.controlled = paper_components ? std::array<bool, 6>{true, true, true, false, false, true}
                                               : std::array<bool, 6>{true, true, true, true, true, true};
  return m;
}

// A synthetic replay: the bases circle, torn in the middle, a failed step.
ReplayResult SyntheticResult(int bases, bool failed) {
  ReplayResult r;
  for (int i = 0; i <= 100; ++i) {
    ReplaySample s;
    s.time = 0.05 * i;
    s.commanded << 0.01 * std::sin(s.time), 0.002 * s.time, 0.6, 0, 0, 0.01 * s.time;
    s.tracked = s.commanded;
    s.tracked[0] += 1e-4 * std::cos(7 * s.time);
    s.set_controls.resize(3 * bases);
    s.true_controls.resize(3 * bases);
    for (int k = 0; k < bases; ++k) {
      const double a = 2 * M_PI * k / bases;
      s.set_controls.segment<3>(3 * k) << 0.6 * std::cos(a) + 0.01 * std::sin(s.time), 0.6 * std::sin(a), a;
      s.true_controls.segment<3>(3 * k) = s.set_controls.segment<3>(3 * k) + Eigen::Vector3d(1e-3, -1e-3, 0);
    }
    s.torn = failed && i >= 40 && i < 60;
    s.residual_energy = s.torn ? 0.1 : 1e-9;
    r.samples.push_back(s);
  }
  r.torn_residual_energy = 1e-5;
  r.duration_s = 5;
  if (failed) {
    r.converged = false;
    r.warning = "waypoint 1 not reached";
    r.failed_step_time = 3.5;
    r.torn = true;
    r.torn_samples = 20;
    r.first_torn_time = 2.0;
    r.max_residual_energy = 0.1;
  }
  return r;
}

TEST(ReplayPlots, HostileNamesRunNoCommandAndThePlotsAreWritten) {
  SKIP_WITHOUT_GNUPLOT();
  for (const int bases : {3, 48}) {
    const fs::path dir = FreshDir("replay_" + std::to_string(bases));
    const Model m = HostileModel(bases, bases == 3);
    const ReplayResult r = SyntheticResult(bases, true);
    WriteReplayCsv(dir.string(), m, r);
    std::string warning;
    const std::vector<std::string> plots = PlotReplay(dir.string(), m, r, std::string("path") + kHostile, &warning);
    EXPECT_EQ(warning, "");
    EXPECT_EQ(plots.size(), 4u);
    for (const char* f : {"end_effector.png", "end_effector.svg", "bases_xy.png", "bases_xy.svg"}) {
      EXPECT_GT(fs::exists(dir / f) ? fs::file_size(dir / f) : 0, 1000u) << f;
    }
    EXPECT_FALSE(fs::exists(dir / "PWNED")) << "a name ran a command";
    // The script names no folder, only the fixed files in its own.
    const std::string script = Slurp(dir / "replay.gnuplot");
    EXPECT_EQ(script.find(dir.string()), std::string::npos);
    EXPECT_EQ(script.find("system('touch"), std::string::npos);  // names only as quoted strings
  }
}

TEST(ReplayPlots, TheScriptMarksFailuresAndShowsControlledComponentsOnly) {
  const Model m = HostileModel(3, true);
  const std::string failed = ReplayPlotScript(m, SyntheticResult(3, true), "p.csv");
  EXPECT_NE(failed.find("SIMULATION"), std::string::npos);
  EXPECT_NE(failed.find("FAILED: the control solution did not reach a waypoint"), std::string::npos);
  EXPECT_NE(failed.find("FAILED: chain torn"), std::string::npos);
  EXPECT_NE(failed.find("set arrow 1 from first 3.5"), std::string::npos);  // the failed step
  EXPECT_NE(failed.find("set object 1000 rect from first 1.975"), std::string::npos);  // the torn band
  EXPECT_NE(failed.find("set ylabel 'yaw [rad]'"), std::string::npos);
  EXPECT_EQ(failed.find("set ylabel 'roll"), std::string::npos);  // not controlled
  const std::string fine = ReplayPlotScript(m, SyntheticResult(3, false), "p.csv");
  EXPECT_EQ(fine.find("FAILED"), std::string::npos);
  EXPECT_EQ(fine.find("\nset object"), std::string::npos);
  EXPECT_EQ(fine.find("\nset arrow"), std::string::npos);
  // Many bases: no key entry per base.
  const std::string many = ReplayPlotScript(HostileModel(48, false), SyntheticResult(48, false), "p.csv");
  EXPECT_EQ(many.find("title ('b0"), std::string::npos);
  EXPECT_NE(ReplayPlotScript(HostileModel(3, false), SyntheticResult(3, false), "p.csv").find("title ('b0"),
            std::string::npos);
}

// Bases starting at `starts` (x, y [m]), each moving straight by `travel`
// over 101 samples; tracked = set.
ReplayResult StraightPaths(const std::vector<Eigen::Vector2d>& starts, const Eigen::Vector2d& travel) {
  ReplayResult r;
  for (int i = 0; i <= 100; ++i) {
    ReplaySample s;
    s.time = 0.05 * i;
    s.commanded = s.tracked = Eigen::VectorXd::Zero(6);
    s.set_controls.resize(3 * static_cast<int>(starts.size()));
    for (size_t k = 0; k < starts.size(); ++k) {
      const Eigen::Vector2d p = starts[k] + travel * (i / 100.0);
      s.set_controls.segment<3>(3 * static_cast<int>(k)) << p.x(), p.y(), 0;
    }
    s.true_controls = s.set_controls;
    s.residual_energy = 1e-20;
    r.samples.push_back(s);
  }
  r.duration_s = 5;
  return r;
}

Model NamedBases(int n) {
  Model m;
  m.name = "m";
  for (int k = 0; k < n; ++k) m.mobile_bases.push_back(MobileBase{});
  for (int k = 0; k < n; ++k) m.mobile_bases[k].name = "b" + std::to_string(k);
  m.end_effector.controlled = {true, true, true, false, false, true};
  return m;
}

// The script of bases_xy.png in a replay's script.
std::string BasesPng(const std::string& script) {
  const size_t begin = script.find("set output 'bases_xy.png'");
  return begin == std::string::npos ? "" : script.substr(begin, script.find("set output\n", begin) - begin);
}

// The bases' plot fits its ranges to the paths (equal axes, a margin); a few
// bases far apart get one window each at one scale, so centimetre paths show.
TEST(ReplayPlots, TheBasesPlotFitsThePaths) {
  // One base, 1 cm along x at y = 0.5: the path and 5 mm (kMinWindow / 2) around it.
  const std::string one = BasesPng(ReplayPlotScript(NamedBases(1), StraightPaths({{0, 0.5}}, {0.01, 0}), "p.csv"));
  EXPECT_NE(one.find("set size ratio -1\n"), std::string::npos);
  EXPECT_NE(one.find("set xrange [-0.005:0.015]\nset yrange [0.495:0.505]\n"), std::string::npos) << one;
  EXPECT_EQ(one.find("set multiplot"), std::string::npos);
  // Three bases 1 m apart, each 2 cm along x: the layout (margin 5 % of its
  // 2.02 m; the height widened to a third of the width, no sliver), then a 3 cm window (2 cm + 20 %, rounded up) around each path.
  const std::string three =
      BasesPng(ReplayPlotScript(NamedBases(3), StraightPaths({{0, 0}, {1, 0}, {2, 0}}, {0.02, 0}), "p.csv"));
  EXPECT_NE(three.find("set multiplot layout 2,2"), std::string::npos) << three;
  EXPECT_NE(three.find("the 3 cm windows of the panels"), std::string::npos);
  EXPECT_NE(three.find("set xrange [-0.101:2.121]\nset yrange [-0.37033333"), std::string::npos) << three;
  for (const char* window : {"set title 'b0'\nset xrange [-0.005:0.025]\nset yrange [-0.015:0.015]\n",
                             "set title 'b1'\nset xrange [0.995:1.025]\nset yrange [-0.015:0.015]\n",
                             "set title 'b2'\nset xrange [1.995:2.025]\nset yrange [-0.015:0.015]\n"}) {
    EXPECT_NE(three.find(window), std::string::npos) << window;
  }
  // Paths as large as the layout: one frame.
  const std::string large =
      BasesPng(ReplayPlotScript(NamedBases(3), StraightPaths({{0, 0}, {1, 0}, {2, 0}}, {0, 0.8}), "p.csv"));
  EXPECT_NE(large.find("set size ratio -1\n"), std::string::npos);
  EXPECT_EQ(large.find("set multiplot"), std::string::npos);
  SKIP_WITHOUT_GNUPLOT();
  const fs::path dir = FreshDir("zoomed");
  const ReplayResult r = StraightPaths({{0, 0}, {1, 0}, {2, 0}}, {0.02, 0});
  WriteReplayCsv(dir.string(), NamedBases(3), r);
  std::string warning;
  EXPECT_EQ(PlotReplay(dir.string(), NamedBases(3), r, "p.csv", &warning).size(), 4u);
  EXPECT_EQ(warning, "");
  EXPECT_GT(fs::file_size(dir / "bases_xy.png"), 1000u);
}

TEST(ReplayReport, ComponentsFollowTheModel) {
  EXPECT_EQ(ReportedComponents(HostileModel(3, true)), (std::vector<int>{kY, kZ, kX, kYaw}));
  EXPECT_EQ(ReportedComponents(HostileModel(3, false)), (std::vector<int>{kX, kY, kZ, kRoll, kPitch, kYaw}));
  Model planar = HostileModel(3, false);
  planar.end_effector.controlled = {true, true, false, false, false, true};
  EXPECT_EQ(ReportedComponents(planar), (std::vector<int>{kX, kY, kYaw}));
}

TEST(ReplayReport, TheTableWarnsAndShowsPaperRowsOnlyForThePaperModels) {
  Model m = HostileModel(3, true);
  const std::string failed = ReplayRmseTable(m, SyntheticResult(3, true), "a test");
  EXPECT_EQ(failed.rfind("WARNING: NOT TRUSTWORTHY", 0), 0u) << failed;
  EXPECT_NE(failed.find("did not reach every waypoint"), std::string::npos);
  EXPECT_NE(failed.find("torn in 20 samples"), std::string::npos);
  EXPECT_NE(failed.find("| source | y [mm] | z [mm] | x [mm] | yaw [rad] |"), std::string::npos) << failed;
  EXPECT_EQ(failed.find("paper"), std::string::npos);
  m.name = "4dof_reduced";
  const std::string paper = ReplayRmseTable(m, SyntheticResult(3, false), "a test");
  EXPECT_EQ(paper.find("WARNING"), std::string::npos);
  EXPECT_NE(paper.find("| paper, reduced scheme, sequential (Fig. 7) | 18 | 12 | 17 | 0.09 |"), std::string::npos)
      << paper;
  const std::string six = ReplayRmseTable(HostileModel(3, false), SyntheticResult(3, false), "a test");
  EXPECT_NE(six.find("| source | x [mm] | y [mm] | z [mm] | roll [rad] | pitch [rad] | yaw [rad] |"),
            std::string::npos)
      << six;
}

TEST(ReplayReport, TheCsvHeadersCarryUnitsAndTheTornColumn) {
  const fs::path dir = FreshDir("csv");
  WriteReplayCsv(dir.string(), HostileModel(2, true), SyntheticResult(2, true));
  std::ifstream ee(dir / "end_effector.csv");
  std::string comment, header, row;
  std::getline(ee, comment);
  std::getline(ee, header);
  EXPECT_NE(comment.find("SIMULATION"), std::string::npos);
  EXPECT_EQ(header.rfind("time_s,cmd_x_m,cmd_y_m,cmd_z_m,cmd_roll_rad", 0), 0u) << header;
  EXPECT_NE(header.find(",err_x_mm,"), std::string::npos);
  EXPECT_EQ(header.substr(header.size() - 24), ",residual_energy_m2,torn");
  int torn = 0;
  while (std::getline(ee, row)) torn += row.back() == '1';
  EXPECT_EQ(torn, 20);
  std::ifstream bases(dir / "bases.csv");
  std::getline(bases, comment);
  std::getline(bases, header);
  EXPECT_EQ(comment.find('\n'), std::string::npos);
  EXPECT_EQ(header, "time_s,set0_x_m,set0_y_m,set0_theta_rad,base0_x_m,base0_y_m,base0_theta_rad,set1_x_m,set1_y_m,"
                    "set1_theta_rad,base1_x_m,base1_y_m,base1_theta_rad,torn");
}

}  // namespace
}  // namespace ccma::cli
