// Reading an untrusted file path safely (declared in formats/model_loader.h,
// shared by the model and waypoint loaders): only regular files, never
// blocking on a FIFO or reading a device, at most a given size.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "formats/model_loader.h"
#include "ccma/internal/format.h"

namespace ccma {
namespace {


// Closes a file descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

std::string TooLarge(const std::string& path, std::size_t max_bytes, const char* noun) {
  return path + ": larger than " + FormatMiB(max_bytes) + " (the limit for a " + noun + ")";
}

}  // namespace

namespace internal {

int OpenRegularFile(const std::string& path, std::size_t max_bytes, const char* noun, std::string* error) {
  const std::string cannot_open = path + ": cannot open the " + noun;
  // Look before opening: opening a FIFO blocks, reading a device never ends.
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    *error = cannot_open + " (no such file)";
    return -1;
  }
  if (ec) {
    *error = cannot_open + " (" + ec.message() + ")";
    return -1;
  }
  if (status.type() != std::filesystem::file_type::regular) {
    const bool directory = status.type() == std::filesystem::file_type::directory;
    *error = path + ": not a regular file" + (directory ? " (a directory)" : "");
    return -1;
  }
  // O_NONBLOCK and the fstat below: the path may have been swapped since.
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (fd.get() < 0) {
    *error = cannot_open + " (" + std::strerror(errno) + ")";
    return -1;
  }
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0 || !S_ISREG(info.st_mode)) {
    *error = path + ": not a regular file";
    return -1;
  }
  if (info.st_size > 0 && static_cast<std::uintmax_t>(info.st_size) > max_bytes) {
    *error = TooLarge(path, max_bytes, noun);
    return -1;
  }
  return fd.release();
}

bool ReadRegularFile(const std::string& path, std::size_t max_bytes, const char* noun,
                     std::string* text, std::string* error) {
  const FileDescriptor fd(OpenRegularFile(path, max_bytes, noun, error));
  if (fd.get() < 0) return false;
  const std::string too_large = TooLarge(path, max_bytes, noun);
  text->clear();
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd.get(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      *error = path + ": cannot read the " + noun + " (" + std::strerror(errno) + ")";
      return false;
    }
    if (got == 0) break;
    if (text->size() + static_cast<std::size_t>(got) > max_bytes) {
      *error = too_large;  // it grew, or st_size was not its size
      return false;
    }
    text->append(buffer, static_cast<std::size_t>(got));
  }
  return true;
}

}  // namespace internal
}  // namespace ccma
