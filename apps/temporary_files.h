// The temporaries ccma makes beside its outputs -- OutputFile's
// `.NAME.ccma-tmp-<pid>-XXXXXX` files and MakeScratchFolder's
// `.ccma-plot-<pid>-XXXXXX` folders (apps/output_file.h) -- removed when the
// `ccma` tool is stopped by SIGINT (Ctrl-C), SIGTERM or SIGHUP, instead of
// staying behind, hidden and up to hundreds of MB, until a later run of
// the same output counts them stale (issue 49).
//
// A fixed table of paths, filled and emptied as temporaries come and go,
// and a signal handler that removes what the table holds with
// async-signal-safe calls only (unlink, open, getdents64, unlinkat, rmdir),
// then ends the process by the same signal with its default action: the
// parent still sees a death by SIGINT (a shell: exit status 130).
#ifndef CCMA_APPS_TEMPORARY_FILES_H_
#define CCMA_APPS_TEMPORARY_FILES_H_

#include <signal.h>

#include <string>

namespace ccma::cli {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (the tool's main
// does, first thing; the Python module does not: an interpreter keeps its
// own handlers, and its KeyboardInterrupt unwinds to OutputFile's
// destructor, which removes the temporary). A signal ignored at that
// moment (a background job's SIGINT) stays ignored.
void RemoveTemporariesOnSignal();

// Adds `path` (a file, or with `folder` a folder whose entries are files)
// to the table; a path longer than the table's slots (4095 bytes), or a
// full table (64 entries), is not added and simply stays behind if a
// signal comes.
void RegisterTemporary(const std::string& path, bool folder = false);

// While it lives, SIGINT, SIGTERM and SIGHUP are held back in the calling
// thread (delivered when it ends): a temporary made and registered under it
// is never left behind by a signal that came in between. Enough where one
// thread runs (OutputFile's --out, made before a command's workers start);
// a workspace store's tiles are written while InterruptWatch holds the
// signals in every thread.
class HoldSignals {
 public:
  HoldSignals();
  ~HoldSignals();
  HoldSignals(const HoldSignals&) = delete;
  HoldSignals& operator=(const HoldSignals&) = delete;

 private:
  sigset_t old_;
};

// Takes `path` out of the table (after it was renamed into place or
// removed).
void ForgetTemporary(const std::string& path);

// Removes every temporary in the table now. Async-signal-safe: the signal
// handler calls it, and so does InterruptWatch's watcher before it ends
// the process by a signal it took itself (apps/interrupt_watch.h).
void RemoveTemporaries();

}  // namespace ccma::cli

#endif  // CCMA_APPS_TEMPORARY_FILES_H_
