// The one place where the `ccma` tool talks to gnuplot.
//
// Safety: gnuplot is started without a shell (posix_spawn, argument vector
// {"gnuplot"}), the script goes to its stdin, and it runs in the output
// folder, so scripts name only fixed relative files (end_effector.csv, ...)
// and never a user's path. Every other string that enters a script (titles
// with model and base names) goes through GnuplotQuote.
#ifndef CCMA_APPS_GNUPLOT_H_
#define CCMA_APPS_GNUPLOT_H_

#include <string>

#include "ccma/internal/format.h"

namespace ccma::cli {

// A gnuplot string expression whose value is `text`, safe for any input:
// single-quoted, where gnuplot expands neither backquotes (command
// substitution) nor @macros nor backslash escapes. Control characters such
// as newline, which would end the command, become '?'. Quotes: gnuplot's
// documented '' for a quote fails where a quote follows another quote (its
// scanner ends the string there: '''a' is '' followed by 'a'), so text with
// quotes becomes a parenthesized concatenation of single-quoted runs and
// "'" (a double-quoted string holding just a quote): it's -> ('it'."'".'s').
// Accepted wherever the scripts here take a string (titles, labels, key
// entries, data file names). Use with `noenhanced` text (set globally by
// TerminalCommand), so the text is also shown literally.
std::string GnuplotQuote(const std::string& text);

// OneLine (ccma/internal/format.h): text for one line of a script.

// The gnuplot executable found on PATH (searched here, not by a shell), or "".
std::string FindGnuplot();

// Runs gnuplot on `script` (written to its stdin through a pipe) with
// `working_dir` as its working directory; its stdout goes to /dev/null, its
// stderr is kept for the message. Never throws: returns "" on success, else
// why it failed (not found, could not start, exit status and first error).
std::string RunGnuplot(const std::string& script, const std::string& working_dir);

// n colours as far apart as hue allows, "#rrggbb", for item i in [0, n).
std::string DistinctColour(int i, int n);

// `set terminal` for "png" (cairo) or "svg" with a size in pixels.
std::string TerminalCommand(const std::string& format, int width, int height);

}  // namespace ccma::cli

#endif  // CCMA_APPS_GNUPLOT_H_
