// Writing an output file the user named, without ever destroying what the
// name points at, and without writing through a name someone else planted:
//  * a regular file (or a new name): written to a fresh temporary file in
//    the same folder, `.NAME.ccma-tmp-<pid>-XXXXXX` (unpredictable, made by
//    mkostemp with O_CREAT | O_EXCL | O_NOFOLLOW, so a planted link there
//    is never followed), given the mode of the file it replaces (else 0666 less the
//    umask), fsync'ed and renamed over NAME on Commit(), so nothing is
//    half-written. Temporaries of a killed run (their pid gone, unmodified
//    for kStaleTemporarySeconds) are removed by the next write to NAME;
//  * a symbolic link: the same, at the link's final target, so the link
//    stays a link (its target's type is never replaced);
//  * a device, FIFO or socket (/dev/null, /dev/stdout): written in place,
//    never replaced by a plain file;
//  * a directory: refused (UsageError, exit 2).
// That is for a name the user gave (--out). A name ccma makes up itself (a
// store's files, the closure file beside `export --out`) is opened with
// ExistingName::kReplace: whatever entry is at the name (a planted link,
// FIFO or device included) is replaced by the new file, never followed or
// written into; only a directory is refused.
// Without Commit() (an exception on the way), the temporary file is removed;
// so is it, and a scratch folder, when the tool is stopped by SIGINT,
// SIGTERM or SIGHUP (apps/temporary_files.h).
// Replacing NAME gives it a new inode: other hard links to the old file keep
// the old content.
#ifndef CCMA_APPS_OUTPUT_FILE_H_
#define CCMA_APPS_OUTPUT_FILE_H_

#include <memory>
#include <ostream>
#include <streambuf>
#include <string>

namespace ccma::cli {

// Age (seconds, by modification time) after which a leftover temporary of
// ours (`.NAME.ccma-tmp-*`, `.ccma-plot-*`) whose writing process no
// longer runs counts as a killed run's.
constexpr long kStaleTemporarySeconds = 600;

// What OutputFile does with an entry already at the name (see above).
enum class ExistingName {
  kFollow,   // a name the user gave: a link is followed, a device written in place
  kReplace,  // a name ccma derives: any entry but a directory is replaced
};

class OutputFile {
 public:
  // `flag` names the flag in messages (e.g. "out"). Throws UsageError when
  // the path cannot be written.
  OutputFile(const std::string& path, const std::string& flag, ExistingName existing = ExistingName::kFollow);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return stream_; }
  // Flushes, fsyncs and moves the file into place; throws
  // std::runtime_error on failure.
  void Commit();

 private:
  std::string path_;       // as given
  std::string target_;     // where the content ends up
  std::string temporary_;  // empty when writing in place
  int fd_ = -1;
  std::unique_ptr<std::streambuf> buffer_;
  std::ostream stream_{nullptr};
  bool committed_ = false;

  void OpenTemporary(bool follow);  // fd_ and temporary_, beside target_
};

// A fresh private folder `DIR/.ccma-plot-<pid>-XXXXXX` (mode 0700) for files that
// are then moved into DIR with MoveIntoFolder (plots drawn by gnuplot,
// which opens its outputs itself). Stale ones of killed runs are removed
// first. Throws UsageError (naming `flag`) when DIR is not writable.
std::string MakeScratchFolder(const std::string& dir, const std::string& flag);

// Renames scratch/name to dir/name: whatever entry dir/name was (a planted
// symbolic link included) is replaced, never followed. False on failure.
bool MoveIntoFolder(const std::string& scratch, const std::string& name, const std::string& dir);

// Removes `scratch` and whatever is left in it (links are removed, not followed).
void RemoveScratchFolder(const std::string& scratch);

// Several files for one folder DIR (`bench --out`, `replay --out`): they are
// written (plainly, gnuplot included) in a scratch folder made by
// MakeScratchFolder, which nobody else can write into, and Commit() moves
// every regular file there into DIR with MoveIntoFolder: an entry of DIR
// with one of their names, a planted symbolic link included, is replaced,
// never written through. Without Commit() (an exception on the way) the
// scratch folder and its files are removed.
class FolderOutput {
 public:
  // `dir` must exist; `flag` names the flag in messages. Throws UsageError
  // when it cannot be written into.
  FolderOutput(const std::string& dir, const std::string& flag);
  ~FolderOutput();
  FolderOutput(const FolderOutput&) = delete;
  FolderOutput& operator=(const FolderOutput&) = delete;

  // Where to write the files (an absolute or DIR-relative path).
  const std::string& scratch() const { return scratch_; }
  // DIR/name: where a file written as scratch()/name ends up.
  std::string Final(const std::string& path_in_scratch) const;
  // Moves the files into DIR; throws std::runtime_error naming the first
  // that could not be moved.
  void Commit();

 private:
  std::string dir_;
  std::string flag_;
  std::string scratch_;
};

// An output folder (--out of `ccma replay`, `ccma bench`), created with its
// parents if missing; one this run created is removed again, if still empty,
// when the run does not finish (a refusal: nothing written). Throws
// UsageError "<who>: --out: cannot create ..." when it cannot be made.
class OutputDirectory {
 public:
  OutputDirectory(const std::string& dir, const std::string& who);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;
  // The run finished: the folder stays.
  void Keep() { kept_ = true; }

 private:
  const std::string dir_;
  bool created_ = false, kept_ = false;
};

}  // namespace ccma::cli

#endif  // CCMA_APPS_OUTPUT_FILE_H_
