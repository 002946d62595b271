#include "formats/internal/sdformat_console.h"

#include <cstdlib>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>

#include <sdf/Console.hh>

namespace ccma {
namespace internal {

void QuietSdformatConsole() {
  static std::once_flag once;
  std::call_once(once, [] {
    const char* home = std::getenv("HOME");
    const std::optional<std::string> saved = home != nullptr ? std::optional<std::string>(home) : std::nullopt;
    ::unsetenv("HOME");
    std::ostringstream swallowed;  // "No HOME defined in the environment. Will not log."
    std::streambuf* const cerr = std::cerr.rdbuf(swallowed.rdbuf());
    struct Restore {
      std::streambuf* cerr;
      const std::optional<std::string>& home;
      ~Restore() {
        std::cerr.rdbuf(cerr);
        if (home) ::setenv("HOME", home->c_str(), 1);
      }
    } restore{cerr, saved};
    sdf::Console::Instance()->SetQuiet(true);
  });
}

}  // namespace internal
}  // namespace ccma
