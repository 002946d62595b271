#include "apps/temporary_files.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstring>

namespace ccma::cli {
namespace {

constexpr std::size_t kSlots = 64;
constexpr std::size_t kPathBytes = 4096;  // with the terminating 0

// One entry of the table. state: kFree, kBusy (being filled or emptied: the
// handler skips it), kFile or kFolder (path holds a whole path).
enum State : int { kFree = 0, kBusy = 1, kFile = 2, kFolder = 3 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathBytes];
};
static_assert(std::atomic<int>::is_always_lock_free, "the handler reads the states without locking");
Slot slots[kSlots];

// Removes the entries of the folder `path` (files; a folder inside is
// left: ccma's scratch folders hold files only), then the folder itself.
// Only async-signal-safe calls: getdents64 through syscall(2), no opendir.
void RemoveFolder(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) char buffer[4096];
    for (long n; (n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer)) > 0;) {
      for (long at = 0; at < n;) {
        struct Entry {
          unsigned long long ino;
          long long off;
          unsigned short reclen;
          unsigned char type;
          char name[1];
        };
        const Entry* entry = reinterpret_cast<const Entry*>(buffer + at);
        const bool dot = entry->name[0] == '.' &&
                         (entry->name[1] == '\0' || (entry->name[1] == '.' && entry->name[2] == '\0'));
        if (!dot) ::unlinkat(fd, entry->name, 0);
        at += entry->reclen;
      }
    }
    ::close(fd);
  }
  ::rmdir(path);
}

void OnSignal(int signal_number) {
  const int saved_errno = errno;
  RemoveTemporaries();
  errno = saved_errno;
  // End as the signal would have ended the process without the handler.
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  ::sigaction(signal_number, &fallback, nullptr);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, signal_number);
  ::pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  ::raise(signal_number);
}

}  // namespace

void RemoveTemporariesOnSignal() {
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (::sigaction(s, nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;
    struct sigaction handler {};
    handler.sa_handler = OnSignal;
    sigemptyset(&handler.sa_mask);
    for (const int other : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&handler.sa_mask, other);  // one at a time
    ::sigaction(s, &handler, nullptr);
  }
}

HoldSignals::HoldSignals() {
  sigset_t held;
  sigemptyset(&held);
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, s);
  ::pthread_sigmask(SIG_BLOCK, &held, &old_);
}

HoldSignals::~HoldSignals() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

void RegisterTemporary(const std::string& path, bool folder) {
  if (path.empty() || path.size() >= kPathBytes) return;
  for (Slot& slot : slots) {
    int expected = kFree;
    if (!slot.state.compare_exchange_strong(expected, kBusy)) continue;
    std::memcpy(slot.path, path.c_str(), path.size() + 1);
    slot.state.store(folder ? kFolder : kFile);
    return;
  }
}

void ForgetTemporary(const std::string& path) {
  for (Slot& slot : slots) {
    int state = slot.state.load();
    if (state != kFile && state != kFolder) continue;
    if (std::strcmp(slot.path, path.c_str()) != 0) continue;
    if (slot.state.compare_exchange_strong(state, kBusy)) slot.state.store(kFree);
    return;
  }
}

void RemoveTemporaries() {
  for (Slot& slot : slots) {
    const int state = slot.state.load();
    if (state == kFile) ::unlink(slot.path);
    if (state == kFolder) RemoveFolder(slot.path);
  }
}

}  // namespace ccma::cli
