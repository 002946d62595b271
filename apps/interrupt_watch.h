// Saying what a long command leaves behind when it is stopped (Ctrl-C).
//
// While an InterruptWatch lives, SIGINT and SIGTERM are blocked in the thread
// that made it and in every thread started from it afterwards, and one
// watcher thread waits for them (sigtimedwait). When one arrives, the watcher
// calls `report` -- in an ordinary thread, not a signal handler, so it may
// lock, allocate and print -- removes the temporaries of unfinished outputs
// (apps/temporary_files.h), and then ends the process by that same signal
// with its default action: the parent sees a death by SIGINT (a shell: exit
// status 130), as without the watch. A signal the process ignores when the
// watch starts (a background job's SIGINT) stays ignored.
//
// Make the watch before the threads whose work it reports are started, and
// end it before starting programs that should get Ctrl-C themselves (a
// child inherits the blocked mask).
#ifndef CCMA_APPS_INTERRUPT_WATCH_H_
#define CCMA_APPS_INTERRUPT_WATCH_H_

#include <signal.h>

#include <atomic>
#include <functional>
#include <thread>

namespace ccma::cli {

class InterruptWatch {
 public:
  explicit InterruptWatch(std::function<void(int signal)> report);
  ~InterruptWatch();  // stops the watcher; restores the signal mask
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

 private:
  void Watch();
  const std::function<void(int)> report_;
  sigset_t watched_;
  sigset_t old_mask_;
  std::atomic<bool> stop_{false};
  std::thread watcher_;
};

}  // namespace ccma::cli

#endif  // CCMA_APPS_INTERRUPT_WATCH_H_
