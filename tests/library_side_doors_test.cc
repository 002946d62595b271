// The libraries ccma links write no file of their own (issue 49):
// libsdformat's console would open $HOME/.sdformat/sdformat.log with
// O_TRUNC through a link planted there, and glog, once initialised, writes
// log files into $GLOG_log_dir (or /tmp). ccma writes only the paths the
// user gives (docs/security.md, "Libraries").
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <glog/logging.h>
#include <gtest/gtest.h>

#include "apps/library_logging.h"
#include "tests/tool_run.h"

namespace ccma {
namespace library_side_doors_test {

namespace fs = std::filesystem;

// HOME set to `home` for the life of the object (the tool inherits it).
class ScopedHome {
 public:
  explicit ScopedHome(const std::string& home) {
    if (const char* old = std::getenv("HOME")) old_ = old;
    setenv("HOME", home.c_str(), 1);
  }
  ~ScopedHome() {
    if (old_) {
      setenv("HOME", old_->c_str(), 1);
    } else {
      unsetenv("HOME");
    }
  }

 private:
  std::optional<std::string> old_;
};

std::string FreshDir(const std::string& name) {
  const std::string dir = testing::ScratchPath("side_doors", name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// `ccma import` of an SDFormat file (the four-bar of tests/data).
testing::ToolRun ImportFourBar(const std::string& out) {
  return testing::RunTool({"import", "--from=" + std::string(CCMA_TEST_DATA_DIR) + "/four_bar_loop.sdf",
                           "--actuated=crank", "--end_effector=coupler", "--out=" + out});
}

// A link planted at $HOME/.sdformat/sdformat.log pointing at a file of the
// user's: an SDFormat import leaves the file as it was and the link a link.
TEST(LibrarySideDoors, SdformatImportDoesNotWriteThroughAPlantedLogLink) {
  const std::string dir = FreshDir("planted"), home = dir + "/home", victim = dir + "/victim.txt";
  fs::create_directories(home + "/.sdformat");
  std::ofstream(victim) << "precious\n";
  fs::create_symlink(victim, home + "/.sdformat/sdformat.log");
  const ScopedHome scoped(home);
  const testing::ToolRun run = ImportFourBar(dir + "/robot.yaml");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(testing::Slurp(victim), "precious\n");
  EXPECT_TRUE(fs::is_symlink(home + "/.sdformat/sdformat.log"));
  EXPECT_EQ(run.err.find("HOME"), std::string::npos) << run.err;  // libsdformat's "will not log" swallowed
}

// Nor does it make $HOME/.sdformat where there is none.
TEST(LibrarySideDoors, SdformatImportMakesNothingUnderHome) {
  const std::string dir = FreshDir("fresh"), home = dir + "/home";
  fs::create_directories(home);
  const ScopedHome scoped(home);
  const testing::ToolRun run = ImportFourBar(dir + "/robot.yaml");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(fs::is_empty(home));
}

// glog as the tool sets it up (cli::InitLibraryLogging): a Ceres error goes
// to stderr, and no log file appears in the folder $GLOG_log_dir names.
TEST(LibrarySideDoors, GlogWritesNoLogFile) {
  const std::string dir = FreshDir("glog");
  FLAGS_log_dir = dir;  // what GLOG_log_dir=DIR sets before main
  cli::InitLibraryLogging("library_side_doors_test");
  ::testing::internal::CaptureStderr();
  LOG(ERROR) << "a message as Ceres logs one";
  const std::string err = ::testing::internal::GetCapturedStderr();
  google::FlushLogFiles(google::GLOG_INFO);
  EXPECT_NE(err.find("a message as Ceres logs one"), std::string::npos) << err;
  EXPECT_TRUE(fs::is_empty(dir)) << fs::directory_iterator(dir)->path();
  google::ShutdownGoogleLogging();
}

}  // namespace library_side_doors_test
}  // namespace ccma
