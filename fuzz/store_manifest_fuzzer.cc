// libFuzzer target for the manifest of a `ccma workspace --store` store
// (DIR/store.json, apps/workspace_store_manifest.h, issue 34).
//
// Any text is either the manifest of the fixed map below, the manifest of
// another map, or refused as malformed with a printable reason; anything
// else (an exception, a crash, a sanitizer report) aborts. Seeds:
// fuzz/corpus_store_manifest/.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "apps/workspace_store_manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // The manifest of a map named "fuzz" in 16 tiles (what the seeds hold).
    static const std::string want = ccma::cli::StoreManifestText("fuzz", 16);
    std::string why;
    const ccma::cli::ManifestMatch match = ccma::cli::CheckStoreManifest(text, want, &why);
    if ((match == ccma::cli::ManifestMatch::kMalformed) == why.empty()) {
      std::fprintf(stderr, "store_manifest_fuzzer: a reason given or missing: '%s'\n", why.c_str());
      std::abort();
    }
    for (char c : why) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) {
        std::fprintf(stderr, "store_manifest_fuzzer: an unprintable reason\n");
        std::abort();
      }
    }
    if (text == want && match != ccma::cli::ManifestMatch::kSame) {
      std::fprintf(stderr, "store_manifest_fuzzer: its own manifest refused\n");
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "store_manifest_fuzzer: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
