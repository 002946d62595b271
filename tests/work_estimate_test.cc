// The estimate of a run's time (analyses/work_estimate.h) on a clock the test
// sets: when it is judged, said and refused, the words it uses, and that a
// refusal stops every later update. The commands that use it:
// work_bound_cli_test.cc.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analyses/work_estimate.h"

namespace ccma {
namespace work_estimate_test {

// Options on a clock at `*now` [s], lines into `*said`.
WorkEstimateOptions Options(const double* now, std::vector<std::string>* said, double max_minutes = 10) {
  WorkEstimateOptions o;
  o.who = "ccma workspace";
  o.noun = "samples";
  o.max_minutes = max_minutes;
  o.raise_with = "--max_minutes";
  o.say = [said](const std::string& line) { said->push_back(line); };
  o.clock = [now] { return *now; };
  return o;
}

TEST(WorkEstimate, ShortRunsSayNothing) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimate e(Options(&now, &said), 100);
  for (int i = 1; i <= 100; ++i) {
    now = 0.04 * i;  // 4 s in all: below the 5 s that are announced
    e.Update(i);
  }
  EXPECT_TRUE(said.empty());
  EXPECT_NEAR(e.estimated_seconds(), 4.0, 1e-9);
}

// 0.27 ms a sample, a million samples: 270 s, said after the 2 s of
// calibration, then a line every 10 s with what is left.
TEST(WorkEstimate, ALongRunIsAnnouncedThenReportedEveryTenSeconds) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimate e(Options(&now, &said), 1000000);
  for (long long done = 1000; done <= 1000000; done += 1000) {
    now = 0.27e-3 * static_cast<double>(done);
    e.Update(done);
    if (done == 7000) EXPECT_TRUE(said.empty());  // 1.9 s: still calibrating
  }
  ASSERT_GE(said.size(), 2u);
  EXPECT_EQ(said[0], "ccma workspace: about 4 min 30 s for 1,000,000 samples (0.27 ms each); progress every 10 s");
  EXPECT_EQ(said[1], "ccma workspace: 46,000 of 1,000,000 samples (5 %) in 12 s; about 4 min 18 s left");
  // 270 s: the announcement at 2.2 s, then a line at least every 10 s.
  EXPECT_EQ(said.size(), 1u + 26u);
}

TEST(WorkEstimate, ARunBeyondTheBoundIsRefusedOnceCalibrated) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimate e(Options(&now, &said, 2), 1000);  // 2 minutes allowed
  now = 1.5;
  e.Update(1);  // calibrating
  now = 2.0;
  try {
    e.Update(2);  // 1 s a unit: 1000 s, 16.7 min
    FAIL() << "not refused";
  } catch (const WorkBoundError& error) {
    EXPECT_EQ(std::string(error.what()),
              "ccma workspace: about 16 min 40 s for 1,000 samples (1.0 s each), more than the 2 min that "
              "--max_minutes=2 allows: give --max_minutes=20 or more to run it, or ask for less work");
  }
  now = 3;  // every later update (another thread's) stops too
  EXPECT_THROW(e.Update(3), WorkBoundError);
}

TEST(WorkEstimate, KnownLaterWorkCountsAndAloneCanRefuse) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimate e(Options(&now, &said), 100);
  e.AddLaterSeconds(100, "the CSV's computed columns");
  now = 2;
  e.Update(50);  // 40 ms a sample: 2 + 2 + 100 s
  EXPECT_NEAR(e.estimated_seconds(), 104, 1e-9);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0],
            "ccma workspace: about 1 min 44 s for 100 samples (40 ms each, then 1 min 40 s for the CSV's computed "
            "columns); progress every 10 s");
  WorkEstimate hours(Options(&now, &said), 1000000);
  EXPECT_THROW(hours.AddLaterSeconds(3600, "the CSV's computed columns"), WorkBoundError);
}

// Design: the iterations of reach and margin, then the objective's, timed on
// their own; a stage that may not refuse is only said.
TEST(WorkEstimate, AStageIsTimedOnItsOwn) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimateOptions o = Options(&now, &said, 10);
  o.who = "ccma design";
  o.noun = "design iterations";
  o.up_to = true;
  WorkEstimate e(o, 2000);
  for (int i = 1; i <= 40; ++i) {
    now = 0.05 * i;
    e.Update(i);  // 50 ms each: 100 s for up to 2,000
  }
  EXPECT_NEAR(e.estimated_seconds(), 100, 1e-6);
  e.BeginStage("design iterations of the deflection objective", 1000, 0, true);
  now += 1.7;
  e.Update(1);  // calibrating
  now += 1.7;
  try {
    e.Update(2);
    FAIL() << "not refused";
  } catch (const WorkBoundError& error) {
    EXPECT_NE(std::string(error.what()).find("for up to 1,000 design iterations of the deflection objective (1.7 s "
                                             "each), more than the 10 min"),
              std::string::npos)
        << error.what();
  }
  WorkEstimate rows(Options(&now, &said), 10);
  rows.BeginStage("rows of the CSV", 1000, 0, false);
  now += 3;
  EXPECT_NO_THROW(rows.Update(1));  // 3 s a row: 50 min, but never refused
}

TEST(WorkEstimate, AnEstimateThatGrowsPastTwiceTheBoundStopsTheRun) {
  double now = 0;
  std::vector<std::string> said;
  WorkEstimate e(Options(&now, &said, 1), 1000);
  now = 2;
  e.Update(100);  // 20 ms each: 20 s
  now = 12;
  e.Update(200);  // 60 ms each: 60 s, the bound, not twice it
  now = 40;
  EXPECT_THROW(e.Update(210), WorkBoundError);  // 190 ms each: 190 s
}

TEST(WorkEstimate, BoundsAndWords) {
  double now = 0;
  std::vector<std::string> said;
  EXPECT_THROW(WorkEstimate(Options(&now, &said, 0), 1), std::invalid_argument);
  EXPECT_THROW(WorkEstimate(Options(&now, &said, 10081), 1), std::invalid_argument);
  EXPECT_EQ(FormatDuration(0.00027), "0.27 ms");
  EXPECT_EQ(FormatDuration(0.69), "690 ms");
  EXPECT_EQ(FormatDuration(4.25), "4.2 s");
  EXPECT_EQ(FormatDuration(51), "51 s");
  EXPECT_EQ(FormatDuration(278), "4 min 38 s");
  EXPECT_EQ(FormatDuration(1678), "27 min 58 s");
  EXPECT_EQ(FormatDuration(7500), "2 h 5 min");
  EXPECT_EQ(FormatCount(0), "0");
  EXPECT_EQ(FormatCount(999), "999");
  EXPECT_EQ(FormatCount(1000000), "1,000,000");
  EXPECT_EQ(FormatCount(-12345), "-12,345");
}

}  // namespace work_estimate_test
}  // namespace ccma
