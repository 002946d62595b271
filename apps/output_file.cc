#include "apps/output_file.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include "apps/cli.h"

namespace ccma::cli {

namespace fs = std::filesystem;

OutputFile::OutputFile(const std::string& path, const std::string& flag) : path_(path) {
  if (path.empty()) throw UsageError("--" + flag + ": empty path");
  std::error_code ec;
  // Follow symbolic links to the file they name (which may not exist yet).
  target_ = path;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target_, ec)); ++hops) {
    if (hops == 40) throw UsageError("--" + flag + ": too many levels of symbolic links in '" + path + "'");
    const fs::path link = fs::read_symlink(target_, ec);
    if (ec) throw UsageError("--" + flag + ": cannot read the link '" + path + "': " + ec.message());
    target_ = (link.is_absolute() ? link : fs::path(target_).parent_path() / link).string();
  }
  const fs::file_status status = fs::status(target_, ec);
  if (fs::is_directory(status)) throw UsageError("--" + flag + ": '" + path + "' is a directory");
  const bool special = fs::exists(status) && !fs::is_regular_file(status);
  if (!special) temporary_ = target_ + ".partial." + std::to_string(::getpid());
  stream_.open(special ? target_ : temporary_, std::ios::out | std::ios::trunc | std::ios::binary);
  if (!stream_) {
    if (!temporary_.empty()) std::remove(temporary_.c_str());
    throw UsageError("--" + flag + ": cannot write '" + path + "'");
  }
}

OutputFile::~OutputFile() {
  if (!committed_ && !temporary_.empty()) {
    stream_.close();
    std::remove(temporary_.c_str());
  }
}

void OutputFile::Commit() {
  stream_.close();
  if (!stream_) throw std::runtime_error("could not write '" + path_ + "'");
  if (!temporary_.empty() && std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    std::remove(temporary_.c_str());
    throw std::runtime_error("could not write '" + path_ + "'");
  }
  committed_ = true;
}

}  // namespace ccma::cli
