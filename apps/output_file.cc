#include "apps/output_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "apps/cli.h"
#include "apps/temporary_files.h"

namespace ccma::cli {

namespace fs = std::filesystem;

namespace {

// A stream buffer over a file descriptor we opened ourselves (std::ofstream
// can only open by name, which would follow whatever is at the name).
class FdBuffer : public std::streambuf {
 public:
  explicit FdBuffer(int fd) : fd_(fd), data_(1 << 16) { setp(data_.data(), data_.data() + data_.size()); }

 protected:
  int_type overflow(int_type c) override {
    if (!Drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return Drain() ? 0 : -1; }

 private:
  bool Drain() {
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      p += n;
    }
    setp(data_.data(), data_.data() + data_.size());
    return true;
  }
  int fd_;
  std::vector<char> data_;
};

// Whether the process whose id starts `rest` ("<pid>-XXXXXX", as Unique()
// names it) still runs; false when `rest` names no process.
bool WriterRuns(const std::string& rest) {
  char* end = nullptr;
  const long pid = std::strtol(rest.c_str(), &end, 10);
  if (end == rest.c_str() || *end != '-' || pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

// The template of a fresh name in `dir`: PREFIX<pid>-XXXXXX. The pid lets a
// later run tell a killed writer's leftover from a running one's; the
// random suffix keeps the name unpredictable.
std::string Unique(const fs::path& dir, const std::string& prefix) {
  return (dir / (prefix + std::to_string(::getpid()) + "-XXXXXX")).string();
}

// Removes the entries of `dir` whose names start with `prefix`, owned by us
// not modified for kStaleTemporarySeconds and whose writer is gone: what a
// killed run left.
// Links and files are unlinked (never followed), folders removed with their
// content.
void RemoveStale(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  const std::time_t now = std::time(nullptr);
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    struct stat info;
    if (name.compare(0, prefix.size(), prefix) != 0 || ::lstat(it->path().c_str(), &info) != 0) continue;
    if (info.st_uid != ::getuid() || now - info.st_mtime < kStaleTemporarySeconds) continue;
    if (WriterRuns(name.substr(prefix.size()))) continue;  // a long run writes at its end
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

// The mode a new output gets: that of the file it replaces, else 0666 less
// the umask (what open(O_CREAT) would have given it). `follow`: through a
// link at `target` (never for a name whose link is replaced).
mode_t ModeFor(const std::string& target, bool follow) {
  struct stat info;
  const int got = follow ? ::stat(target.c_str(), &info) : ::lstat(target.c_str(), &info);
  if (got == 0 && S_ISREG(info.st_mode)) return info.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

// Makes a rename in `dir` durable; best effort (some file systems refuse).
void SyncFolder(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Follows symbolic links from `path` to the file they name (which may not
// exist yet).
std::string FinalTarget(const std::string& path, const std::string& flag) {
  std::error_code ec;
  std::string target = path;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) throw UsageError("--" + flag + ": too many levels of symbolic links in '" + path + "'");
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) throw UsageError("--" + flag + ": cannot read the link '" + path + "': " + ec.message());
    target = (link.is_absolute() ? link : fs::path(target).parent_path() / link).string();
  }
  return target;
}

}  // namespace

OutputFile::OutputFile(const std::string& path, const std::string& flag, ExistingName existing) : path_(path) {
  if (path.empty()) throw UsageError("--" + flag + ": empty path");
  if (existing == ExistingName::kReplace) {
    target_ = path;  // the entry itself, whatever it is
    struct stat info;
    if (::lstat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
      throw UsageError("--" + flag + ": '" + path + "' is a directory");
    }
    OpenTemporary(false);
  } else {
    target_ = FinalTarget(path, flag);
    std::error_code ec;
    const fs::file_status status = fs::status(target_, ec);
    if (fs::is_directory(status)) throw UsageError("--" + flag + ": '" + path + "' is a directory");
    if (fs::exists(status) && !fs::is_regular_file(status)) {
      fd_ = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);  // a device or FIFO
    } else {
      OpenTemporary(true);
    }
  }
  if (fd_ < 0) throw UsageError("--" + flag + ": cannot write '" + path + "'");
  buffer_ = std::make_unique<FdBuffer>(fd_);
  stream_.rdbuf(buffer_.get());
}

void OutputFile::OpenTemporary(bool follow) {
  const fs::path target(target_);
  const std::string prefix = "." + target.filename().string() + ".ccma-tmp-";
  RemoveStale(target.parent_path(), prefix);
  std::string name = Unique(target.parent_path(), prefix);
  {
    const HoldSignals held;  // a signal between the two is taken after both
    // mkostemp opens with O_CREAT | O_EXCL (mode 0600), retrying names.
    fd_ = ::mkostemp(name.data(), O_CLOEXEC | O_NOFOLLOW);
    if (fd_ >= 0) {
      temporary_ = name;
      RegisterTemporary(temporary_);  // removed if a signal ends the run before Commit
    }
  }
  if (fd_ >= 0 && ::fchmod(fd_, ModeFor(target_, follow)) != 0) {
    ::close(fd_);
    ::unlink(temporary_.c_str());
    ForgetTemporary(temporary_);
    temporary_.clear();
    fd_ = -1;
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) {
    ::unlink(temporary_.c_str());
    ForgetTemporary(temporary_);
  }
}

void OutputFile::Commit() {
  stream_.flush();
  bool ok = static_cast<bool>(stream_);
  // fsync before the rename, so a crash never leaves NAME empty; devices
  // and pipes need none (and may refuse it).
  if (ok && !temporary_.empty()) ok = ::fsync(fd_) == 0;
  ok = ::close(fd_) == 0 && ok;
  fd_ = -1;
  if (ok && !temporary_.empty()) ok = std::rename(temporary_.c_str(), target_.c_str()) == 0;
  if (!ok) throw std::runtime_error("could not write '" + path_ + "'");
  if (!temporary_.empty()) {
    ForgetTemporary(temporary_);  // after the rename: a signal between the two removes nothing
    SyncFolder(fs::path(target_).parent_path());
  }
  committed_ = true;
}

std::string MakeScratchFolder(const std::string& dir, const std::string& flag) {
  RemoveStale(dir, ".ccma-plot-");
  std::string name = Unique(dir, ".ccma-plot-");
  const HoldSignals held;
  if (::mkdtemp(name.data()) == nullptr) throw UsageError("--" + flag + ": cannot write into '" + dir + "'");
  RegisterTemporary(name, true);
  return name;
}

bool MoveIntoFolder(const std::string& scratch, const std::string& name, const std::string& dir) {
  const fs::path from = fs::path(scratch) / name;
  const int fd = ::open(from.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  return std::rename(from.c_str(), (fs::path(dir) / name).c_str()) == 0;
}

void RemoveScratchFolder(const std::string& scratch) {
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
  ForgetTemporary(scratch);
}

FolderOutput::FolderOutput(const std::string& dir, const std::string& flag)
    : dir_(dir), flag_(flag), scratch_(MakeScratchFolder(dir, flag)) {}

FolderOutput::~FolderOutput() { RemoveScratchFolder(scratch_); }

std::string FolderOutput::Final(const std::string& path_in_scratch) const {
  return (fs::path(dir_) / fs::path(path_in_scratch).filename()).string();
}

void FolderOutput::Commit() {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(scratch_, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->symlink_status(ec).type() == fs::file_type::regular) names.push_back(it->path().filename().string());
  }
  if (ec) throw std::runtime_error("--" + flag_ + ": cannot read '" + scratch_ + "': " + ec.message());
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    if (!MoveIntoFolder(scratch_, name, dir_)) {
      throw std::runtime_error("--" + flag_ + ": cannot write '" + (fs::path(dir_) / name).string() + "'");
    }
  }
  SyncFolder(dir_);
}

OutputDirectory::OutputDirectory(const std::string& dir, const std::string& who) : dir_(dir) {
  std::error_code ec;
  created_ = !std::filesystem::exists(dir, ec);
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw UsageError(who + ": --out: cannot create '" + dir + "'");
}

OutputDirectory::~OutputDirectory() {
  std::error_code ec;
  if (created_ && !kept_ && std::filesystem::is_empty(dir_, ec)) std::filesystem::remove(dir_, ec);
}

}  // namespace ccma::cli
