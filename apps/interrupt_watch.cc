#include "apps/interrupt_watch.h"

#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <ctime>
#include <utility>

#include "apps/temporary_files.h"

namespace ccma::cli {

InterruptWatch::InterruptWatch(std::function<void(int)> report) : report_(std::move(report)) {
  sigemptyset(&watched_);
  for (const int s : {SIGINT, SIGTERM}) {
    struct sigaction current {};
    if (sigaction(s, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) sigaddset(&watched_, s);
  }
  // Blocked before the watcher starts: a signal from now on waits for it.
  pthread_sigmask(SIG_BLOCK, &watched_, &old_mask_);
  watcher_ = std::thread([this] { Watch(); });
}

InterruptWatch::~InterruptWatch() {
  stop_.store(true);
  watcher_.join();
  pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
}

void InterruptWatch::Watch() {
  // How soon the destructor's stop is seen; a signal is taken at once.
  const timespec tick{0, 50 * 1000 * 1000};
  while (!stop_.load()) {
    const int signal_number = sigtimedwait(&watched_, nullptr, &tick);
    if (signal_number <= 0) continue;  // the tick ran out, or EINTR
    report_(signal_number);
    RemoveTemporaries();  // the hidden temporaries of unfinished outputs (apps/temporary_files.h)
    // End as the signal would have: default action, unblocked here, raised
    // at this thread (process-wide termination, the parent sees the signal).
    std::signal(signal_number, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, signal_number);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    std::raise(signal_number);
    _exit(128 + signal_number);  // not reached: the default action of both is to terminate
  }
}

}  // namespace ccma::cli
