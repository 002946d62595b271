// Where the libraries the `ccma` tool links may log: stderr only, never a
// file (issue 49). glog (through Ceres), once initialised, writes every
// message at or above FLAGS_minloglevel to log files in $GLOG_log_dir (or
// /tmp) and points a link `ccma.ERROR` there at them: files the user never
// named. libsdformat's console is made without its log file where it is
// used (formats/internal/sdformat_console.h); urdfdom (console_bridge) and
// yaml-cpp write no files (docs/security.md, "Libraries").
#ifndef CCMA_APPS_LIBRARY_LOGGING_H_
#define CCMA_APPS_LIBRARY_LOGGING_H_

namespace ccma::cli {

// Initialises glog for the program `argv0` (call once, first thing in
// main): messages of Ceres at ERROR and above go to stderr, below are
// dropped, and no log file is ever opened, whatever GLOG_* variables say.
void InitLibraryLogging(const char* argv0);

}  // namespace ccma::cli

#endif  // CCMA_APPS_LIBRARY_LOGGING_H_
