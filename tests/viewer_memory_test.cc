// `ccma view`'s memory does not grow with the size of the CSV it reads
// (issue 49 items 7 and 8): a workspace map and a trajectory are read row by
// row, keeping only the columns the page draws and, of a trajectory, only
// the frames it shows. Each test measures the tool's peak resident set
// (wait4) on a wide file against the same command on a small one: the
// difference must stay far below the file's size (a table of every cell,
// as it was, takes eight bytes a cell: five times the file). When memory
// does run out, the message names the file and the status is 2.
// The same at the documented bounds (a 1 GiB map, a 256 MiB trajectory):
// viewer_memory_large_test.cc, CTest label "large".
#include <sys/resource.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/large_csv.h"
#include "tests/tool_run.h"

namespace ccma {
namespace viewer_memory_test {

using testing::ModelPath;
using testing::RunTool;
using testing::ToolRun;

std::string Scratch(const std::string& name) { return testing::ScratchPath("viewer_memory", name); }

ToolRun View(const std::string& flag, const std::string& csv) {
  return RunTool({"view", "--model=" + ModelPath("4dof_reduced"), flag + csv, "--out=" + csv + ".html"});
}

#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer's own memory would be measured

TEST(ViewMemory, AWideWorkspaceMapTakesMemoryForItsPointsNotItsCells) {
  const std::string small = Scratch("small_map.csv"), wide = Scratch("wide_map.csv");
  testing::WriteWideWorkspaceMap(small, 100, 2000);
  const std::uintmax_t bytes = testing::WriteWideWorkspaceMap(wide, 20000, 2000);  // 80 MB
  const ToolRun base = View("--workspace=", small);
  const ToolRun run = View("--workspace=", wide);
  ASSERT_EQ(base.status, 0) << base.err;
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["workspace_points"], 20000);
  EXPECT_EQ(j["workspace_reachable"], 10000);
  const double growth = 1024.0 * static_cast<double>(run.peak_rss_kb - base.peak_rss_kb);
  EXPECT_LT(growth, static_cast<double>(bytes) / 4) << "peak " << run.peak_rss_kb << " KiB against "
                                                    << base.peak_rss_kb << " KiB for " << bytes << " bytes";
  std::filesystem::remove(wide);
}

TEST(ViewMemory, ALongWideTrajectoryTakesMemoryForTheFramesShown) {
  const std::string waypoints = Scratch("lift.csv"), source = Scratch("lift_path.csv");
  std::ofstream(waypoints) << "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n2,0,0.03,0.62,0,0,0\n";
  const ToolRun made =
      RunTool({"trajectory", "--model=" + ModelPath("4dof_reduced"), "--waypoints=" + waypoints, "--out=" + source});
  ASSERT_EQ(made.status, 0) << made.err;
  const std::string small = Scratch("small_path.csv"), wide = Scratch("wide_path.csv");
  testing::WriteLongTrajectory(small, source, 3000, 2000);
  const std::uintmax_t bytes = testing::WriteLongTrajectory(wide, source, 40000, 2000);  // 80 MB
  const ToolRun base = View("--trajectory=", small);
  const ToolRun run = View("--trajectory=", wide);
  ASSERT_EQ(base.status, 0) << base.err;
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["frames"], 2000);  // thinned to the page's bound
  const double growth = 1024.0 * static_cast<double>(run.peak_rss_kb - base.peak_rss_kb);
  EXPECT_LT(growth, static_cast<double>(bytes) / 4) << "peak " << run.peak_rss_kb << " KiB against "
                                                    << base.peak_rss_kb << " KiB for " << bytes << " bytes";
  std::filesystem::remove(wide);
}

// The child's address space capped at 150 MB.
void CapAddressSpace() {
  const rlimit limit{std::uint64_t{150} << 20, std::uint64_t{150} << 20};
  setrlimit(RLIMIT_AS, &limit);
}

// With too little memory for a page of a million points (the address space
// capped at 150 MB: the page needs about 160 MB), the file is named and the
// status is 2, never std::bad_alloc with status 1 (nor an abort in a
// destructor that allocates).
TEST(ViewMemory, RunningOutOfMemoryNamesTheFile) {
  const std::string map = Scratch("million.csv");
  testing::WriteWideWorkspaceMap(map, 1000000, 0);
  const ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--workspace=" + map,
                             "--out=" + Scratch("million.html")},
                            120, CapAddressSpace);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("ccma view: " + map + ": not enough memory"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(Scratch("million.html")));
  std::filesystem::remove(map);
}

#endif

}  // namespace viewer_memory_test
}  // namespace ccma
