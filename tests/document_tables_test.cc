// The commands' tables (documents/table.h): the CSV cells of each column
// kind, and the replay's and the workspace map's columns at closed-form
// values (wrapped angle errors, unreached samples).
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "ccma/ccma.h"
#include "documents/replay_report.h"
#include "documents/table.h"
#include "documents/workspace_table.h"

namespace ccma::documents {
namespace document_tables_test {

TEST(DocumentTable, EachKindWritesItsCells) {
  Table t;
  t.Add("x_m").values = {0.1, std::numeric_limits<double>::infinity(), std::nan(""), -2.5};
  t.Add("reached", ColumnKind::kFlag).values = {1, 0, 2, 0};
  t.Add("wave", ColumnKind::kCount).values = {3, -1, 9007199254740992.0, 0};
  t.Add("limited_by", ColumnKind::kText).texts = {"a,b", "q\"1\nq2", "", "j"};
  std::ostringstream csv;
  WriteCsv(t, csv);
  EXPECT_EQ(csv.str(),
            "x_m,reached,wave,limited_by\n"
            "0.10000000000000001,1,3,a;b\n"
            ",0,-1,q;1;q2\n"
            ",1,9007199254740992,\n"
            "-2.5,0,0,j\n");
  std::ostringstream short_digits;
  WriteCsv(t, short_digits, 12);
  EXPECT_EQ(short_digits.str().substr(short_digits.str().find('\n') + 1, 6), "0.1,1,");
  EXPECT_EQ(CsvSafeText("a,\"b\"\r\n"), "a;;b;;;");
}

TEST(DocumentTable, ColumnsOfDifferentLengthsAreRefused) {
  Table t;
  t.Add("a").values = {1, 2};
  t.Add("b", ColumnKind::kText).texts = {"x"};
  std::ostringstream csv;
  EXPECT_THROW(WriteCsv(t, csv), std::logic_error);
  EXPECT_EQ(t.rows(), 2u);
}

// One replay sample whose yaw crosses +-pi: err_yaw_rad is the wrapped
// difference (-0.2 rad, not 2 pi - 0.2), positions in mm.
TEST(DocumentTable, ReplayErrorsAreWrappedAnglesAndMillimetres) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  ReplayResult r;
  ReplaySample s;
  s.time = 0.5;
  s.commanded << 0.1, 0.2, 0.3, 0, 0, M_PI - 0.1;
  s.tracked << 0.1005, 0.2, 0.3, 0, 0, -M_PI + 0.1;
  s.set_controls = s.true_controls = model.home_controls();
  s.residual_energy = std::nan("");
  s.torn = true;
  r.samples.push_back(s);
  const Table ee = ReplayEndEffectorTable(r);
  ASSERT_EQ(ee.rows(), 1u);
  for (const Column& c : ee.columns) {
    if (c.name == "err_yaw_rad") EXPECT_NEAR(c.values[0], 0.2, 1e-12);
    if (c.name == "err_x_mm") EXPECT_NEAR(c.values[0], 0.5, 1e-9);
    if (c.name == "torn") EXPECT_EQ(c.kind, ColumnKind::kFlag);
  }
  EXPECT_EQ(ee.columns.front().name, "time_s");
  EXPECT_EQ(ee.columns.back().name, "torn");
  std::ostringstream csv;
  WriteCsv(ee, csv, kReplayCsvDigits);
  EXPECT_NE(csv.str().find(",,1\n"), std::string::npos) << csv.str();  // E not a number: an empty cell, torn 1
  const Table bases = ReplayBasesTable(model, r);
  // time, set and true controls of every base, one column per actuated joint, torn.
  EXPECT_EQ(bases.columns.size(),
            static_cast<std::size_t>(2 + 2 * model.num_base_controls() + model.num_actuated_joints()));
}

// A reached and an unreached sample: the unreached one's controls are empty
// cells, its sigma_min and ee_std_m 0, whatever the samples hold.
TEST(DocumentTable, WorkspaceRowsOfUnreachedSamplesHaveNoControls) {
  const Model model = LoadModel(std::string(CCMA_MODELS_DIR) + "/4dof_reduced.yaml");
  WorkspaceSample reached, missed;
  reached.reachable = true;
  reached.controls = model.home_controls();
  reached.state = State::Home(model);
  reached.sigma_min = 0.3;
  missed = reached;
  missed.reachable = false;
  missed.limited_by = "joint1,joint2";
  const std::vector<WorkspaceSample> samples = {reached, missed};
  const WorkspaceComputedColumns computed = ComputeWorkspaceColumns(model, samples);
  EXPECT_GT(computed.ee_std_m[0], 0);
  EXPECT_EQ(computed.ee_std_m[1], 0);
  EXPECT_EQ(computed.ee_std_m[0], EndEffectorPositionStd(model, reached.state, reached.controls));
  const Table t = WorkspaceTable(model, samples, computed);
  std::ostringstream csv;
  WriteCsv(t, csv);
  std::istringstream lines(csv.str());
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  std::string controls, empty;
  for (int k = 0; k < model.num_controls(); ++k) {
    controls += ",u" + std::to_string(k);
    empty += ",";
  }
  EXPECT_EQ(header.substr(header.find("reachable")),
            "reachable,residual_energy,sigma_min,error,rcond,max_limit_violation,limited_by,wave,start,ee_std_m" +
                controls);
  EXPECT_EQ(second.substr(second.size() - empty.size() - 1), "0" + empty) << second;  // every control empty
  EXPECT_NE(second.find(",0,0,0,0,joint1;joint2,0,-1,0,"), std::string::npos) << second;
  EXPECT_EQ(first.substr(first.size() - 4).find(",,"), std::string::npos) << first;
  EXPECT_THROW(WorkspaceTable(model, {reached}, computed), std::invalid_argument);
}

}  // namespace document_tables_test
}  // namespace ccma::documents
