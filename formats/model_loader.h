// Loading and validating CCMA model files (contract: shared/model_format.md).
//
// Every rejection is a ModelError whose message names the file, the line
// (where YAML gives one) and the offending key or name, e.g.
//   models/bad.yaml:14: joints[2].axis: must not be the zero vector
// Nothing here aborts or prints; callers decide how to report.
//
// Model text is untrusted: names, numbers, counts, sizes and nesting depth are
// checked against the documented ranges of ccma/limits.h before use, and text
// quoted back in a message is escaped and shortened.
#ifndef CCMA_MODEL_LOADER_H_
#define CCMA_MODEL_LOADER_H_

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "ccma/model.h"

namespace ccma {

// A malformed or unreadable model file.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and validates the model file at `path` (YAML, or JSON). Only a
// regular file (symlinks followed) of at most kMaxModelFileBytes is read;
// a directory, device or FIFO is rejected without being opened for reading.
// Throws ModelError on any problem, including a misspelt key: an unknown key
// within edit distance 2 (1 for short keys) of a key that mapping knows, e.g.
//   m.yaml:12: joints[3]: unknown key 'betwen' (did you mean 'between'?)
// When `warnings` is given, the model loads and one line per finding is
// appended to it ("file:line: key: what"; the library prints nothing):
//  - any other unknown key (the format may be extended): ignored;
//  - implausible magnitudes, one line per kind naming the first one: a length
//    above 100 m (millimetres?) or an angle above 2 pi (degrees?).
Model LoadModel(const std::string& path,
                std::vector<std::string>* warnings = nullptr);

// The same for a model held in memory; `source_name` stands in for the file
// name in messages. Text longer than kMaxModelFileBytes is rejected.
Model LoadModelFromString(const std::string& text,
                          const std::string& source_name,
                          std::vector<std::string>* warnings = nullptr);

namespace internal {

// Reads the whole of `path`, which must be a regular file (after following
// symlinks) of at most `max_bytes` bytes, into `text`. On failure returns
// false and sets `error` to a message "path: what" (`noun` names the kind of
// file, e.g. "model file"). Never blocks on a FIFO or reads a device.
// Shared by the model and waypoint loaders.
bool ReadRegularFile(const std::string& path, std::size_t max_bytes, const char* noun,
                     std::string* text, std::string* error);

// The same checks, for a file read in pieces (ccma view's CSVs): returns an
// open descriptor (O_RDONLY | O_CLOEXEC | O_NONBLOCK; the caller closes it)
// of a regular file whose size is at most `max_bytes` when opened, or -1
// with `error` set as above. The reader must still stop past `max_bytes`
// (the file may grow).
int OpenRegularFile(const std::string& path, std::size_t max_bytes, const char* noun, std::string* error);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_MODEL_LOADER_H_
