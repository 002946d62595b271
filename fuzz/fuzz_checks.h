// Checks shared by the fuzz entry points (fuzz/*_fuzzer.cc). Each entry
// point hands its input to one reader; these turn a broken contract into an
// abort, which libFuzzer reports as a finding and the corpus replay
// (fuzz/corpus_replay.cc, CTest fuzz_corpus_replay_<name>) as a failed test.
#ifndef CCMA_FUZZ_FUZZ_CHECKS_H_
#define CCMA_FUZZ_FUZZ_CHECKS_H_

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "ccma/model.h"
#include "formats/model_loader.h"

namespace ccma_fuzz {

// Stops the run: prints `what` (and `detail`) on stderr and aborts.
[[noreturn]] inline void Fail(const std::string& what, const std::string& detail = "") {
  std::fprintf(stderr, "fuzz: %s%s%s\n", what.c_str(), detail.empty() ? "" : ": ", detail.c_str());
  std::abort();
}

// A reader's messages start with the name of what it read ("source:line: ..."
// or "source: ..."): a message that does not is a finding.
inline void ExpectNamesSource(const std::string& message, const std::string& source) {
  if (message.rfind(source, 0) != 0) Fail("message without the source name " + source, message);
}

// A message is one printable line: a name from the file that holds a
// terminal escape sequence or a newline must arrive quoted and escaped.
inline void ExpectOnePrintableLine(const std::string& message) {
  for (const char c : message) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) Fail("control character in a message", message);
  }
}

// Calls read(), which may throw only `Error` (the reader's documented error
// type, whose message must start with one of `sources`, and be one printable
// line when `one_printable_line`); any other exception is a finding.
// Returns whether read() returned normally.
template <typename Error, typename Read>
bool ReadOrRefuse(const std::vector<std::string>& sources, bool one_printable_line, Read read) {
  try {
    read();
    return true;
  } catch (const Error& e) {
    const std::string message = e.what();
    bool named = false;
    for (const std::string& source : sources) named = named || message.rfind(source, 0) == 0;
    if (!named) Fail("message without the source name " + sources.front(), message);
    if (one_printable_line) ExpectOnePrintableLine(message);
  } catch (const std::exception& e) {
    Fail("unexpected exception", e.what());
  } catch (...) {
    Fail("unexpected non-standard exception");
  }
  return false;
}

template <typename Error, typename Read>
bool ReadOrRefuse(const std::string& source, Read read) {
  return ReadOrRefuse<Error>(std::vector<std::string>{source}, false, read);
}

// A model file of the repository (path relative to the source tree, e.g.
// "models/4dof_reduced.yaml"), loaded on first use: the model a file is read
// against. CCMA_SOURCE_DIR is defined by ccma_fuzz_target (fuzz/CMakeLists.txt).
inline const ccma::Model& RepositoryModel(const std::string& relative_path) {
  static std::map<std::string, ccma::Model> models;
  auto it = models.find(relative_path);
  if (it == models.end()) {
    it = models.emplace(relative_path, ccma::LoadModel(std::string(CCMA_SOURCE_DIR) + "/" + relative_path)).first;
  }
  return it->second;
}

}  // namespace ccma_fuzz

#endif  // CCMA_FUZZ_FUZZ_CHECKS_H_
