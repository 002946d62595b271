// Command-line plumbing for the `ccma` tool: flag parsing that never exits
// behind our back, value parsing, and the exit-status contract of cli.md
// (0 ok, 1 failure, 2 bad usage or bad model).
#ifndef CCMA_APPS_CLI_H_
#define CCMA_APPS_CLI_H_

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ccma::cli {

// Bad usage or a bad model file: exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses args (after the sub-command) of the form --name=value or --name
// into gflags, accepting only the flags in `allowed`. Throws UsageError.
void ParseFlags(const std::vector<std::string>& args, const std::set<std::string>& allowed,
                const std::string& command);

// "1.5,-2,3e-3" -> vector; `flag` names the flag in messages. Throws UsageError.
Eigen::VectorXd ParseNumberList(const std::string& text, const std::string& flag);

// The value of a required string flag. Throws UsageError when it is empty.
std::string RequireFlag(const std::string& value, const std::string& flag,
                        const std::string& command);

// The command line that started this process (main.cc hands its argv to
// gflags::SetArgv), each word quoted for a shell where it needs it: 'a b',
// and bash's $'\xNN' for bytes outside printable ASCII, so that it can be
// printed as "run this again" and pasted back.
std::string CommandLineForShell();

}  // namespace ccma::cli

#endif  // CCMA_APPS_CLI_H_
