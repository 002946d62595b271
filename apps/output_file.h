// Writing an output file the user named, without ever destroying what the
// name points at:
//  * a regular file (or a new name): written to a temporary file beside it
//    and renamed over it on Commit(), so nothing is half-written;
//  * a symbolic link: the same, at the link's final target, so the link
//    stays a link (its target's type is never replaced);
//  * a device, FIFO or socket (/dev/null, /dev/stdout): written in place,
//    never replaced by a plain file;
//  * a directory: refused (UsageError, exit 2).
// Without Commit() (an exception on the way), the temporary file is removed.
#ifndef CCMA_APPS_OUTPUT_FILE_H_
#define CCMA_APPS_OUTPUT_FILE_H_

#include <fstream>
#include <string>

namespace ccma::cli {

class OutputFile {
 public:
  // `flag` names the flag in messages (e.g. "out"). Throws UsageError when
  // the path cannot be written.
  OutputFile(const std::string& path, const std::string& flag);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream() { return stream_; }
  // Flushes and moves the file into place; throws std::runtime_error on failure.
  void Commit();

 private:
  std::string path_;       // as given
  std::string target_;     // where the content ends up
  std::string temporary_;  // empty when writing in place
  std::ofstream stream_;
  bool committed_ = false;
};

}  // namespace ccma::cli

#endif  // CCMA_APPS_OUTPUT_FILE_H_
