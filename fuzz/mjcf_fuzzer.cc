// libFuzzer target for the MuJoCo MJCF reader and the importer (issue "trust
// boundaries").
//
// Any input must either import or be rejected with ccma::ModelError naming
// the source; any other exception, a crash, a sanitizer report, a leak, a
// hang or a file opened by MuJoCo (an <include> or a mesh followed) is a bug. The
// corpus fuzz/corpus_mjcf/ holds exported robots and the hostile cases
// of issue 51.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "fuzz/fuzz_checks.h"
#include "fuzz/robot_import_fuzz.h"
#include "formats/model_loader.h"
#include "formats/mjcf_reader.h"

namespace {

constexpr const char* kSource = "fuzz.xml";

void Run(const std::string& input) {
  ccma_fuzz::ImportWhatWasRead(ccma::ReadMjcfFromString(input, kSource, {}), kSource);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  ccma_fuzz::ReadOrRefuse<ccma::ModelError>({kSource}, /*one_printable_line=*/true, [&] { Run(input); });
  return 0;
}
