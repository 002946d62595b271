#include "apps/library_logging.h"

#include <glog/logging.h>

namespace ccma::cli {

void InitLibraryLogging(const char* argv0) {
  google::InitGoogleLogging(argv0);
  FLAGS_logtostderr = true;  // glog's file logging off: GLOG_log_dir, GLOG_logtostderr=0 are ignored
  FLAGS_minloglevel = google::GLOG_ERROR;  // Ceres' own chatter stays quiet
}

}  // namespace ccma::cli
