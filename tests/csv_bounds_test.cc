// The CSV tables `ccma view` reads (viewer/csv_reader.h) are bounded by their
// file: a line may have at most kMaxCsvColumns cells, counted before the line
// is split, so a header of commas is refused at once (exit 2, file and line
// named) instead of becoming one string per cell.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/tool_run.h"
#include "viewer/csv_reader.h"

namespace ccma {
namespace csv_bounds_test {

using testing::ModelPath;
using testing::RunTool;
using testing::ScratchPath;

// A trajectory CSV whose header has `cells` empty cells, then one row.
std::string WriteCommas(const std::string& name, std::size_t cells) {
  const std::string path = ScratchPath("csv_bounds", name);
  std::ofstream out(path, std::ios::binary);
  out << "# ccma trajectory\n" << std::string(cells - 1, ',') << "\n0\n";
  return path;
}

TEST(CsvBounds, AHeaderOfCommasIsRefusedByItsCellCount) {
  const std::size_t cells = viewer::kMaxCsvColumns + 1;
  const std::string csv = WriteCommas("commas.csv", cells);
  const testing::ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=" + csv,
                                      "--out=" + ScratchPath("csv_bounds", "commas.html")});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find(csv + ":2: " + std::to_string(cells) + " cells, more than the 100000 columns"),
            std::string::npos)
      << r.err;
}

TEST(CsvBounds, AtTheBoundTheTableIsReadAndJudgedOnItsContent) {
  // kMaxCsvColumns cells pass the bound; the single-cell row then has the
  // wrong number of cells, which is what the message says.
  const std::string csv = WriteCommas("at_bound.csv", viewer::kMaxCsvColumns);
  const testing::ToolRun r = RunTool({"view", "--model=" + ModelPath("4dof_reduced"), "--trajectory=" + csv,
                                      "--out=" + ScratchPath("csv_bounds", "at_bound.html")});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(csv + ":3: 1 cells, the header has 100000"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace ccma
