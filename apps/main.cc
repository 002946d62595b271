// `ccma`: the command-line tool (docs/cli.md). Dispatches to the sub-commands
// of the registry (commands.h) and maps errors to the exit-status contract:
// 0 ran, 1 failure, 2 bad usage or bad input (message on stderr, nothing on stdout).
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/cli.h"
#include "analyses/work_estimate.h"
#include "apps/commands.h"
#include "apps/library_logging.h"
#include "apps/temporary_files.h"

namespace {

bool IsHelp(const std::string& arg) { return arg == "--help" || arg == "-h" || arg == "help"; }

int Dispatch(const ccma::cli::Command& command, const std::vector<std::string>& args) {
  try {
    return command.run(args);
  } catch (const ccma::cli::UsageError& e) {
    // Every message names the command; those about one flag ("--target:
    // ...") are thrown without it.
    const std::string message = e.what();
    std::cerr << (message.rfind("ccma ", 0) == 0 ? "" : "ccma " + command.name + ": ") << message << "\n";
  } catch (const ccma::ModelError& e) {
    std::cerr << "ccma " << command.name << ": " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {  // input out of its documented range
    std::cerr << "ccma " << command.name << ": " << e.what() << "\n";
  } catch (const ccma::WorkBoundError& e) {  // more work than --max_minutes allows; says how long
    std::cerr << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ccma " << command.name << ": error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  ccma::cli::RemoveTemporariesOnSignal();  // Ctrl-C and SIGTERM leave no hidden temporary behind
  ccma::cli::InitLibraryLogging(argv[0]);  // stderr only, never a log file
  gflags::SetArgv(argc, const_cast<const char**>(argv));  // for CommandLineForShell (cli.h)
  if (argc < 2) {
    std::cerr << ccma::cli::GlobalHelp();
    return 2;
  }
  const std::string name = argv[1];
  if (IsHelp(name)) {
    std::cout << ccma::cli::GlobalHelp();
    return 0;
  }
  if (name == "--version" || name == "version") {
    std::cout << ccma::cli::VersionLine() << "\n";
    return 0;
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const ccma::cli::Command& command : ccma::cli::Commands()) {
    if (command.name != name) continue;
    for (const std::string& arg : args) {
      if (IsHelp(arg)) {
        std::cout << ccma::cli::CommandHelp(command);
        return 0;
      }
    }
    return Dispatch(command, args);
  }
  std::cerr << "ccma: unknown command '" << name << "'\n\n" << ccma::cli::GlobalHelp();
  return 2;
}
