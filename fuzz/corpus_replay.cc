// Replays a fuzz target's corpus through its entry point, without libFuzzer:
// built by the ordinary compiler (gcc is fine) for every target of
// fuzz/targets.cmake whenever tests are built, as fuzz_corpus_replay_<name>
// and registered with CTest under that name, so every input the fuzzer ever
// kept is checked on every test run. Live fuzzing, which needs clang, is
// scripts/fuzz.sh.
//
//   fuzz_corpus_replay_<name> DIR_OR_FILE...
//
// Feeds every regular file of each directory (in name order) or each named
// file to LLVMFuzzerTestOneInput, which aborts on any bug (an exception other
// than the reader's own error, a message without the source name, a result
// that breaks the reader's contract). Exits 0 after printing how many inputs
// ran; 1 when an argument cannot be read or no input was found (an empty
// corpus would test nothing).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

// The inputs named by `arg`: its regular files when it is a directory.
bool CollectInputs(const std::string& arg, std::vector<std::filesystem::path>* inputs) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(arg, ec)) {
    inputs->push_back(arg);
    return true;
  }
  if (!fs::is_directory(arg, ec)) {
    std::fprintf(stderr, "fuzz_corpus_replay: %s: not a file or directory\n", arg.c_str());
    return false;
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(arg, ec)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  inputs->insert(inputs->end(), files.begin(), files.end());
  return !ec;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_corpus_replay DIR_OR_FILE...\n");
    return 1;
  }
  std::vector<std::filesystem::path> inputs;
  for (int i = 1; i < argc; ++i) {
    if (!CollectInputs(argv[i], &inputs)) return 1;
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "fuzz_corpus_replay: no input files found\n");
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  std::size_t bytes = 0;
  for (const std::filesystem::path& path : inputs) {
    std::ifstream in(path, std::ios::binary);
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) {
      std::fprintf(stderr, "fuzz_corpus_replay: cannot read %s\n", path.c_str());
      return 1;
    }
    // Named before it runs: an abort inside leaves this as the last line.
    std::fprintf(stderr, "fuzz_corpus_replay: %s\n", path.c_str());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(data.data()), data.size());
    bytes += data.size();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("fuzz_corpus_replay: %zu inputs (%zu bytes) replayed in %.2f s, no failure\n",
              inputs.size(), bytes, seconds);
  return 0;
}
