// Running gnuplot safely (apps/gnuplot.h): quoting, the child process and
// the terminal settings every plot of the tool shares.
#include "apps/gnuplot.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

extern char** environ;

namespace ccma::cli {
namespace {

// Writes all of `data` to `fd`; "" or why not. SIGPIPE (gnuplot gone) is
// blocked in this thread meanwhile and a SIGPIPE we caused is discarded.
std::string WriteAll(int fd, const std::string& data) {
  sigset_t pipe_set, old_mask, pending;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old_mask);
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE) == 1;
  std::string error;
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = std::string("writing the script to gnuplot failed: ") + std::strerror(errno);
      break;
    }
    done += static_cast<size_t>(n);
  }
  sigpending(&pending);
  if (!was_pending && sigismember(&pending, SIGPIPE) == 1) {
    const timespec zero{0, 0};
    sigtimedwait(&pipe_set, nullptr, &zero);
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  return error;
}

// The first lines of what gnuplot wrote on stderr, for a message.
std::string Excerpt(FILE* file) {
  std::string text;
  std::rewind(file);
  char buffer[4096];
  size_t n;
  while (text.size() < 600 && (n = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, n);
  std::string lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line) && lines.size() < 400;) {
    if (line.find_first_not_of(" \t\r^") == std::string::npos) continue;
    lines += (lines.empty() ? "" : " | ") + OneLine(line);
  }
  return lines.substr(0, 400);
}

}  // namespace

std::string GnuplotQuote(const std::string& text) {
  const std::string run = OneLine(text);
  if (run.find('\'') == std::string::npos) return "'" + run + "'";
  // ('it'."'".'s'): single-quoted runs, each quote as "'" (a double-quoted
  // string holding no backslash and no backquote), joined by `.`.
  std::string out = "(";
  size_t start = 0;
  for (size_t q = run.find('\''); q != std::string::npos; q = run.find('\'', start)) {
    if (q > start) out += "'" + run.substr(start, q - start) + "'.";
    out += "\"'\".";
    start = q + 1;
  }
  if (start < run.size()) out += "'" + run.substr(start) + "'.";
  out.pop_back();  // the last '.'
  return out + ")";
}

std::string FindGnuplot() {
  const char* env = std::getenv("PATH");
  const std::string path = env != nullptr && *env != '\0' ? env : "/usr/local/bin:/usr/bin:/bin";
  std::istringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty() || dir[0] != '/') continue;  // never the working directory
    const std::string candidate = dir + "/gnuplot";
    struct stat info;
    if (stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) && access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return "";
}

std::string RunGnuplot(const std::string& script, const std::string& working_dir) {
  const std::string gnuplot = FindGnuplot();
  if (gnuplot.empty()) return "gnuplot not found on PATH: plots skipped (apt-get install gnuplot-nox)";
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return std::string("cannot create a pipe: ") + std::strerror(errno);
  FILE* err = std::tmpfile();  // gnuplot's stderr: a file, so it can never block gnuplot
  if (err == nullptr) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return std::string("cannot create a temporary file: ") + std::strerror(errno);
  }
  fcntl(fileno(err), F_SETFD, FD_CLOEXEC);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fileno(err), STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&actions, working_dir.c_str());
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, gnuplot.c_str(), &actions, &attributes, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(pipe_fds[0]);
  if (spawned != 0) {
    close(pipe_fds[1]);
    std::fclose(err);
    return "cannot start " + gnuplot + " in '" + OneLine(working_dir) + "': " + std::strerror(spawned);
  }
  const std::string write_error = WriteAll(pipe_fds[1], script);
  close(pipe_fds[1]);  // end of the script: gnuplot exits
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      std::fclose(err);
      return std::string("waiting for gnuplot failed: ") + std::strerror(errno);
    }
  }
  const std::string messages = Excerpt(err);
  std::fclose(err);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && write_error.empty()) return "";
  std::string why = WIFEXITED(status) && WEXITSTATUS(status) != 0
                        ? "gnuplot exited with status " + std::to_string(WEXITSTATUS(status))
                    : WIFSIGNALED(status) ? "gnuplot was killed by signal " + std::to_string(WTERMSIG(status))
                                          : write_error;  // gnuplot ended before reading all of the script
  if (!messages.empty()) why += ": " + messages;
  return why;
}

std::string DistinctColour(int i, int n) {
  static const char* kFew[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd",
                               "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
  if (n <= 8) return kFew[((i % 8) + 8) % 8];
  // Hues around the circle (red left out: it marks failures), alternating
  // brightness so that neighbours differ twice.
  const double h = 6.0 * (0.06 + 0.86 * (i % n) / n), s = 0.85, v = i % 2 ? 0.62 : 0.92;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", static_cast<int>(std::lround(255 * (r + m))),
                static_cast<int>(std::lround(255 * (g + m))), static_cast<int>(std::lround(255 * (b + m))));
  return text;
}

std::string TerminalCommand(const std::string& format, int width, int height) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return (format == "png" ? "set terminal pngcairo" + size + " font 'sans,10' noenhanced\n"
                          : "set terminal svg" + size + " font 'sans,10' noenhanced background rgb 'white'\n");
}

}  // namespace ccma::cli
