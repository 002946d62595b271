// Waypoint files are untrusted input (issue "hostile input"): every hostile
// case is rejected with file:line, quickly, without a crash.
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "ccma/limits.h"
#include "formats/waypoints.h"
#include "tests/tool_run.h"

namespace ccma {
namespace waypoints_test {

const char kHeader[] = "time,x,y,z,roll,pitch,yaw\n";

class WaypointFiles : public ::testing::Test {
 protected:
  WaypointFiles() {
    dir_ = std::filesystem::path(ccma::testing::TestDir()) /
           ("ccma_waypoints_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  ~WaypointFiles() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  std::string File(const std::string& name) const { return (dir_ / name).string(); }

  // Writes `text` to a file and returns the error of loading it ("" if none).
  std::string ErrorOfText(const std::string& text) {
    const std::string path = File("w.csv");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    return ErrorOf(path);
  }

  std::string ErrorOf(const std::string& path) {
    const auto start = std::chrono::steady_clock::now();
    std::string message;
    try {
      LoadWaypoints(path);
    } catch (const WaypointError& e) {
      message = e.what();
    }
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return message;
  }

  std::filesystem::path dir_;
  double seconds_ = 0;
};

TEST_F(WaypointFiles, ReferencePathsStillLoad) {
  const auto w = LoadWaypoints(std::string(CCMA_MODELS_DIR) + "/paths/4dof_sequential.csv");
  ASSERT_GT(w.size(), 2u);
  EXPECT_EQ(w[0].time, 0);
  EXPECT_EQ(w[0].position, Eigen::Vector3d(0, 0, 0.6));
  EXPECT_EQ(w[1].position, Eigen::Vector3d(0, 0.08, 0.6));
  EXPECT_EQ(ErrorOfText(std::string("# c\n\n") + " time, x,y,z,roll,pitch,yaw \r\n" +
                        "-1000000,-10000,10000,0,0,0,-10000\r\n1000000,1e4,0,0,0,0,0"),
            "");
}

struct Hostile {
  std::string what;
  std::string rows;      // after the header
  std::string expected;  // the message must contain this, after "w.csv"
};

void PrintTo(const Hostile& h, std::ostream* os) { *os << h.what; }

class HostileRows : public WaypointFiles, public ::testing::WithParamInterface<Hostile> {};

TEST_F(WaypointFiles, SubnormalNumbersAreNumbers) {
  // strtod flags underflow with ERANGE; 4.9e-324 is still a finite number.
  EXPECT_EQ(ErrorOfText(std::string(kHeader) + "0,4.9e-324,0,0,0,0,1e-320\n"), "");
}

TEST_P(HostileRows, AreRejectedWithFileAndLine) {
  const Hostile& h = GetParam();
  const std::string message = ErrorOfText(kHeader + h.rows);
  EXPECT_NE(message.find("w.csv" + h.expected), std::string::npos)
      << h.what << "\n  got:      " << message << "\n  expected: w.csv" << h.expected;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, HostileRows,
    ::testing::Values(
        Hostile{"1e308 time", "0,0,0,0,0,0,0\n1e308,0,0,0,0,0,0\n",
                ":3: '1e308' must lie in [-1000000, 1000000] (time, s)"},
        Hostile{"overflowing time", "1e309,0,0,0,0,0,0\n", ":2: '1e309' is not a finite number (time)"},
        Hostile{"NaN", "0,0,nan,0,0,0,0\n", ":2: 'nan' is not a finite number (y)"},
        Hostile{"infinity", "0,0,0,0,0,0,-inf\n", ":2: '-inf' is not a finite number (yaw)"},
        Hostile{"huge position", "0,1e5,0,0,0,0,0\n",
                ":2: '1e5' must lie in [-10000, 10000] (x, m)"},
        Hostile{"huge angle", "0,0,0,0,0,-2e4,0\n",
                ":2: '-2e4' must lie in [-10000, 10000] (pitch, rad)"},
        Hostile{"too few values", "0,0,0,0.6,0,0\n", ":2: expected 7 values, got 6"},
        Hostile{"too many values", "0,0,0,0.6,0,0,0,0\n", ":2: expected 7 values, got more"},
        Hostile{"trailing comma", "0,0,0,0.6,0,0,0,\n", ":2: expected 7 values, got more"},
        Hostile{"NUL in a field", std::string("0,1\0x,0,0,0,0,0\n", 16),
                ":2: '1\\x00x' is not a finite number (x)"},
        Hostile{"empty field", "0,,0,0.6,0,0,0\n", ":2: '' is not a finite number (x)"},
        Hostile{"control characters", std::string("0,0\x01\x1b[2J,0,0,0,0,0\n"),
                ":2: '0\\x01\\x1b[2J' is not a finite number (x)"},
        Hostile{"long field", "0," + std::string(100000, '9') + ",0,0,0,0,0\n",
                ":2: '" + std::string(40, '9') + "...' (100000 bytes) is not a finite number (x)"},
        Hostile{"time backwards", "1,0,0,0,0,0,0\n0,0,0,0,0,0,0\n", ":3: time goes backwards"},
        Hostile{"hex float", "0,0x1p3,0,0,0,0,0\n", ":2: '0x1p3' is not a finite number (x)"}),
    [](const auto& info) {
      std::string name = info.param.what;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

TEST_F(WaypointFiles, DevZeroIsRejectedAtOnce) {
  EXPECT_EQ(ErrorOf("/dev/zero"), "/dev/zero: not a regular file");
  EXPECT_LT(seconds_, 1.0);
}

TEST_F(WaypointFiles, DirectoryIsRejected) {
  EXPECT_EQ(ErrorOf(dir_.string()), dir_.string() + ": not a regular file (a directory)");
}

TEST_F(WaypointFiles, FifoIsRejectedWithoutBlocking) {
  const std::string fifo = File("w.csv");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf(fifo), fifo + ": not a regular file");
  EXPECT_LT(seconds_, 1.0);
}

TEST_F(WaypointFiles, MissingFile) {
  EXPECT_EQ(ErrorOf("/nonexistent.csv"), "/nonexistent.csv: cannot open the waypoint file (no such file)");
}

TEST_F(WaypointFiles, FileOver16MiBIsRejected) {
  std::string text = kHeader;
  text.resize(kMaxWaypointFileBytes + 1, '#');  // one comment line, one byte too many
  EXPECT_EQ(ErrorOfText(text), File("w.csv") + ": larger than 16 MiB (the limit for a waypoint file)");
  EXPECT_LT(seconds_, 1.0);
}

// The real limit (1,000,000 waypoints) fits in 14 MB of short rows.
TEST_F(WaypointFiles, AtMostAMillionWaypoints) {
  std::string rows = kHeader;
  const std::string row = "0,0,0,0,0,0,0\n";
  rows.reserve(rows.size() + row.size() * (kMaxWaypoints + 1));
  for (int i = 0; i < kMaxWaypoints; ++i) rows += row;
  const std::string path = File("many.csv");
  std::ofstream(path, std::ios::binary) << rows;
  EXPECT_EQ(LoadWaypoints(path).size(), static_cast<std::size_t>(kMaxWaypoints));
  std::ofstream(path, std::ios::binary | std::ios::app) << row;
  EXPECT_EQ(ErrorOf(path), path + ":" + std::to_string(kMaxWaypoints + 2) +
                               ": more than 1000000 waypoints");
}

// Random bytes and random mutations of a valid file (fixed seed): a
// WaypointError or a valid list, never anything else.
TEST_F(WaypointFiles, RandomTextIsRejectedOrLoaded) {
  std::mt19937 random(7);
  const std::string valid = std::string(kHeader) + "0,0,0,0.6,0,0,0\n5,0,0.08,0.6,0,0,0.1\n";
  using namespace std::string_literals;
  const std::string bytes = "0123456789.,-+eE \t\n\r#xinfa\x00\xff"s;  // with the NUL
  std::uniform_int_distribution<int> pick(0, static_cast<int>(bytes.size()) - 1);
  int loaded = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::string text = valid;
    std::uniform_int_distribution<std::size_t> at(0, text.size() - 1);
    for (int k = 0; k < 3; ++k) text[at(random)] = bytes[pick(random)];
    const std::string path = File("r.csv");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    try {
      for (const Waypoint& w : LoadWaypoints(path)) {
        EXPECT_LE(std::abs(w.time), kMaxTime);
        EXPECT_LE(w.position.cwiseAbs().maxCoeff(), kMaxMagnitude);
        EXPECT_LE(w.rpy.cwiseAbs().maxCoeff(), kMaxMagnitude);
      }
      ++loaded;
    } catch (const WaypointError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(loaded, 0);
  EXPECT_LT(loaded, 500);
}

// The rules a file is held to, for waypoints given in memory (Python's follow,
// plan and replay): every file LoadWaypoints accepts passes, and every value
// it refuses is named with its waypoint and column.
TEST(WaypointList, HoldsListsToTheRulesOfTheFile) {
  const Eigen::Vector3d p(0, 0, 0.6);
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();  // `{}` would leave an Eigen vector uninitialised
  EXPECT_EQ(WaypointListError({}), "");
  EXPECT_EQ(WaypointListError({{0, p, o}, {1, p, o}, {1, p, {0, 0, 0.1}}}), "");
  EXPECT_EQ(WaypointListError({{kMaxTime, p, o}, {kMaxTime, {kMaxMagnitude, 0, -kMaxMagnitude}, o}}), "");
  EXPECT_EQ(WaypointListError({{0, p, o}, {std::nan(""), p, o}}),
            "waypoints[1].time (nan) must be a finite number in [-1e+06, 1e+06] (s)");
  EXPECT_EQ(WaypointListError({{1, p, o}, {0.5, p, o}}),
            "waypoints[1].time (0.5) is smaller than waypoints[0].time (1): time goes backwards");
  EXPECT_EQ(WaypointListError({{0, {0, HUGE_VAL, 0}, o}}),
            "waypoints[0].y (inf) must be a finite number in [-10000, 10000] (m)");
  EXPECT_EQ(WaypointListError({{0, p, {0, 2e4, 0}}}),
            "waypoints[0].pitch (20000) must be a finite number in [-10000, 10000] (rad)");
  EXPECT_EQ(WaypointListError(std::vector<Waypoint>(static_cast<std::size_t>(kMaxWaypoints) + 1)),
            "waypoints: 1000001 of them; at most 1000000 are allowed");
}

}  // namespace
}  // namespace ccma
