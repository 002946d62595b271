// The user documentation against the code it describes:
//  * docs/cli.md documents every command and every flag that `ccma --help`
//    and `ccma COMMAND --help` list, each in that command's section, and
//    mentions no flag a command does not accept;
//  * (docs/cli.md's JSON keys and generated help blocks are checked by
//    tests/cli_json_keys_test.py and scripts/update_cli_docs.py --check);
//  * docs/model_format.md names every key the model loader knows;
//  * README.md and docs/*.md name only files that are in the repository,
//    carry no dates or history of past work, and the README stays a front
//    door (at most 200 lines, one table row per command, its C++ example
//    taken line by line from apps/embed_example.cc).
// The docs are read from CCMA_SOURCE_DIR/docs, or from the folder in the
// environment variable CCMA_DOCS_DIR (to check that an edited copy fails).
#include <fcntl.h>
#include <glob.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/tool_run.h"

namespace docs_test {

struct ToolRun {
  int status = -1;
  std::string out, err;
};

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string TempPath(const std::string& name) {
  return ccma::testing::TestDir() + "/docs_test_" + std::to_string(getpid()) + "_" + name;
}

// Runs the tool (fork/exec, no shell) with stdout and stderr in files.
ToolRun Ccma(const std::vector<std::string>& args) {
  static int counter = 0;
  const std::string tag = std::to_string(counter++);
  const std::string out_path = TempPath("out" + tag), err_path = TempPath("err" + tag);
  std::vector<std::string> argv_strings = {CCMA_TOOL_PATH};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0) _exit(127);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  ToolRun run;
  int status = 0;
  if (pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status)) run.status = WEXITSTATUS(status);
  run.out = Slurp(out_path);
  run.err = Slurp(err_path);
  std::remove(out_path.c_str());
  std::remove(err_path.c_str());
  return run;
}

std::string DocsDir() {
  const char* override_dir = std::getenv("CCMA_DOCS_DIR");
  return override_dir != nullptr && *override_dir != '\0' ? override_dir : std::string(CCMA_SOURCE_DIR) + "/docs";
}

std::string ReadDoc(const std::string& name) {
  const std::string text = Slurp(DocsDir() + "/" + name);
  EXPECT_FALSE(text.empty()) << DocsDir() + "/" + name << " is missing or empty";
  return text;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) lines.push_back(line);
  return lines;
}

bool IsWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// ---- what the tool says about itself --------------------------------------

// The commands `ccma --help` lists ("  ccma NAME ..." lines).
std::vector<std::string> ToolCommands() {
  const ToolRun r = Ccma({"--help"});
  EXPECT_EQ(r.status, 0) << r.err;
  std::vector<std::string> commands;
  for (const std::string& line : Lines(r.out)) {
    const std::string prefix = "  ccma ";
    if (line.rfind(prefix, 0) != 0) continue;
    std::string name;
    for (size_t i = prefix.size(); i < line.size() && IsWordChar(line[i]); ++i) name += line[i];
    if (!name.empty()) commands.push_back(name);
  }
  return commands;
}

// The flags `ccma COMMAND --help` lists ("  --name=..." lines after "flags:").
std::vector<std::string> HelpFlags(const std::string& command) {
  const ToolRun r = Ccma({command, "--help"});
  EXPECT_EQ(r.status, 0) << r.err;
  std::vector<std::string> flags;
  bool in_flags = false;
  for (const std::string& line : Lines(r.out)) {
    if (line == "flags:") {
      in_flags = true;
      continue;
    }
    if (!in_flags) continue;
    if (line.rfind("  --", 0) != 0) continue;
    std::string name;
    for (size_t i = 4; i < line.size() && IsWordChar(line[i]); ++i) name += line[i];
    if (!name.empty()) flags.push_back(name);
  }
  return flags;
}

struct ToolFacts {
  std::vector<std::string> commands;
  std::map<std::string, std::set<std::string>> flags;  // per command
};

const ToolFacts& Facts() {
  static const ToolFacts facts = [] {
    ToolFacts f;
    f.commands = ToolCommands();
    for (const std::string& c : f.commands) {
      const std::vector<std::string> flags = HelpFlags(c);
      f.flags[c] = std::set<std::string>(flags.begin(), flags.end());
    }
    return f;
  }();
  return facts;
}

// Flags that every command accepts (handled before the command runs).
bool IsGlobalFlag(const std::string& flag) { return flag == "help" || flag == "version"; }

// ---- docs/cli.md structure ------------------------------------------------

// Position just after "ccma NAME" in `text` at or after `from` (NAME followed
// by a non-word character or the end), or npos.
size_t FindCommandMention(const std::string& text, const std::string& name, size_t from = 0) {
  const std::string needle = "ccma " + name;
  for (size_t p = text.find(needle, from); p != std::string::npos; p = text.find(needle, p + 1)) {
    const size_t end = p + needle.size();
    const bool starts_word = p == 0 || !IsWordChar(text[p - 1]);
    if (starts_word && (end == text.size() || !IsWordChar(text[end]))) return end;
  }
  return std::string::npos;
}

bool IsLevel2Heading(const std::string& line) { return line.rfind("## ", 0) == 0; }
bool IsLevel1Heading(const std::string& line) { return line.rfind("# ", 0) == 0; }
bool IsFence(const std::string& line) {
  const size_t first = line.find_first_not_of(' ');
  return first != std::string::npos && line.compare(first, 3, "```") == 0;
}

// The lines of the command's section: from the first level-2 heading (outside
// code blocks) that names "ccma COMMAND" to the next level-1 or level-2 heading.
std::vector<std::string> CommandSection(const std::string& doc, const std::string& command) {
  std::vector<std::string> section;
  bool in_code = false, inside = false;
  for (const std::string& line : Lines(doc)) {
    if (IsFence(line)) in_code = !in_code;
    const bool heading = !in_code && (IsLevel2Heading(line) || IsLevel1Heading(line));
    if (heading && inside) break;
    if (heading && IsLevel2Heading(line) && FindCommandMention(line, command) != std::string::npos) inside = true;
    if (inside) section.push_back(line);
  }
  return section;
}

// `--name` in `text`, as a whole flag name.
bool MentionsFlag(const std::string& text, const std::string& flag) {
  const std::string needle = "--" + flag;
  for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) {
    const size_t end = p + needle.size();
    const bool starts = p == 0 || !(IsWordChar(text[p - 1]) || text[p - 1] == '-');
    if (starts && (end == text.size() || !IsWordChar(text[end]))) return true;
  }
  return false;
}

struct FlagMention {
  std::string flag;
  std::string command;  // the command it is given to; empty when not known
  int line;             // 1-based, in the document
  std::string text;     // the line
};

// The command named by the last "ccma NAME" (NAME a tool command) in `text`
// before `limit`, else the first one after it; "" if none.
std::string CommandIn(const std::string& text, size_t limit) {
  size_t latest_end = 0, first_after = std::string::npos;
  std::string latest, after;
  for (const std::string& c : Facts().commands) {
    for (size_t end = FindCommandMention(text, c); end != std::string::npos; end = FindCommandMention(text, c, end)) {
      if (end <= limit && end >= latest_end) {
        latest_end = end;
        latest = c;
      } else if (end > limit && end < first_after) {
        first_after = end;
        after = c;
      }
    }
  }
  return !latest.empty() ? latest : after;
}

// Every `--flag` in docs/cli.md with the command it belongs to: the command
// of the "ccma NAME" invocation it is written in (the same inline code span,
// which may run over several lines of a paragraph, or the same command line
// in a code block, continuation lines included), else the command whose
// section it is in ("" outside command sections).
std::vector<FlagMention> FlagMentions(const std::string& doc) {
  std::vector<FlagMention> mentions;
  const std::vector<std::string> lines = Lines(doc);
  std::string section_command;

  // Flags in `text` (a code-block line, or a code span or prose run of a
  // paragraph); `first_line` is the document line where `text` starts.
  auto scan = [&](const std::string& text, bool code, const std::string& fallback, size_t first_line) {
    for (size_t p = text.find("--"); p != std::string::npos; p = text.find("--", p + 2)) {
      if (p > 0 && (IsWordChar(text[p - 1]) || text[p - 1] == '-')) continue;
      std::string name;
      for (size_t i = p + 2; i < text.size() && IsWordChar(text[i]); ++i) name += text[i];
      // Lower-case names only: `--NAME=VALUE` is a placeholder.
      if (name.empty() || !std::islower(static_cast<unsigned char>(name[0]))) continue;
      std::string command = code ? CommandIn(text, p) : "";
      if (command.empty()) command = fallback;
      const size_t line = first_line + static_cast<size_t>(std::count(text.begin(), text.begin() + p, '\n'));
      mentions.push_back({name, command, static_cast<int>(line + 1), lines[line]});
    }
  };

  // A prose paragraph (consecutive non-blank lines): split at backticks.
  std::vector<std::string> paragraph;
  size_t paragraph_start = 0;
  auto flush = [&]() {
    std::string text;
    for (size_t i = 0; i < paragraph.size(); ++i) text += (i ? "\n" : "") + paragraph[i];
    size_t piece_start = 0;
    bool code = false;
    for (size_t i = 0; i <= text.size(); ++i) {
      if (i == text.size() || text[i] == '`') {
        const std::string piece = text.substr(piece_start, i - piece_start);
        const size_t line = paragraph_start + static_cast<size_t>(std::count(text.begin(), text.begin() + piece_start, '\n'));
        scan(piece, code, section_command, line);
        code = !code;
        piece_start = i + 1;
      }
    }
    paragraph.clear();
  };

  bool in_code = false;
  std::string continued_command;  // code: the command of a line ending in '\'
  for (size_t n = 0; n < lines.size(); ++n) {
    const std::string& line = lines[n];
    if (IsFence(line)) {
      flush();
      in_code = !in_code;
      continued_command.clear();
      continue;
    }
    if (in_code) {
      const std::string here = CommandIn(line, line.size());
      scan(line, true, continued_command.empty() ? section_command : continued_command, n);
      const bool continues = !line.empty() && line.back() == '\\';
      continued_command = continues ? (here.empty() ? continued_command : here) : "";
      continue;
    }
    if (IsLevel1Heading(line) || IsLevel2Heading(line)) {
      flush();
      section_command.clear();
      for (const std::string& c : Facts().commands) {
        if (IsLevel2Heading(line) && section_command.empty() && FindCommandMention(line, c) != std::string::npos) {
          section_command = c;
        }
      }
    }
    if (line.find_first_not_of(" \t") == std::string::npos) {
      flush();
      continue;
    }
    if (paragraph.empty()) paragraph_start = n;
    paragraph.push_back(line);
  }
  flush();
  return mentions;
}

// ---- (a) and (b): flags ---------------------------------------------------

TEST(CliDocs, ToolListsItsCommands) {
  const std::set<std::string> commands(Facts().commands.begin(), Facts().commands.end());
  for (const char* expected : {"check", "simulate", "control", "trajectory", "generate", "bench", "replay", "view"}) {
    EXPECT_EQ(commands.count(expected), 1u) << expected;
  }
  for (const std::string& c : Facts().commands) EXPECT_FALSE(Facts().flags.at(c).empty()) << c;
}

TEST(CliDocs, EveryCommandHasASection) {
  const std::string doc = ReadDoc("cli.md");
  for (const std::string& c : Facts().commands) {
    EXPECT_FALSE(CommandSection(doc, c).empty()) << "docs/cli.md has no '## ... ccma " << c << "' section";
  }
}

TEST(CliDocs, EveryHelpFlagIsDocumentedInItsCommandsSection) {
  const std::string doc = ReadDoc("cli.md");
  for (const std::string& c : Facts().commands) {
    std::string section;
    for (const std::string& line : CommandSection(doc, c)) section += line + "\n";
    for (const std::string& flag : Facts().flags.at(c)) {
      EXPECT_TRUE(MentionsFlag(section, flag))
          << "`ccma " << c << " --help` lists --" << flag << ", but the section of ccma " << c
          << " in docs/cli.md does not mention it";
    }
  }
}

TEST(CliDocs, EveryDocumentedFlagIsAcceptedByItsCommand) {
  const std::string doc = ReadDoc("cli.md");
  const std::vector<FlagMention> mentions = FlagMentions(doc);
  EXPECT_GT(mentions.size(), 50u);
  for (const FlagMention& m : mentions) {
    if (IsGlobalFlag(m.flag)) continue;
    if (m.command.empty()) {
      // Outside any command's section and invocation: some command must take it.
      bool accepted = false;
      for (const auto& [command, flags] : Facts().flags) accepted = accepted || flags.count(m.flag) > 0;
      EXPECT_TRUE(accepted) << "docs/cli.md:" << m.line << ": --" << m.flag << " is no flag of any command\n"
                            << m.text;
      continue;
    }
    EXPECT_EQ(Facts().flags.at(m.command).count(m.flag), 1u)
        << "docs/cli.md:" << m.line << ": --" << m.flag << " is documented for ccma " << m.command
        << ", which does not accept it (ccma " << m.command << " --help)\n"
        << m.text;
  }
}

// The attribution rule itself, on a small document.
TEST(CliDocs, FlagMentionsAreAttributedToTheirCommand) {
  const std::string doc =
      "## `ccma control`\n"
      "Use `--lambda` and `ccma simulate --from=X.json` or\n"
      "```sh\n"
      "ccma trajectory --model=m.yaml \\\n"
      "    --waypoints=w.csv\n"
      "--method=lm\n"
      "```\n"
      "## Recipes\n"
      "plain --seed\n";
  std::map<std::string, std::string> by_flag;
  for (const FlagMention& m : FlagMentions(doc)) by_flag[m.flag] = m.command;
  EXPECT_EQ(by_flag["lambda"], "control");
  EXPECT_EQ(by_flag["from"], "simulate");
  EXPECT_EQ(by_flag["model"], "trajectory");
  EXPECT_EQ(by_flag["waypoints"], "trajectory");
  EXPECT_EQ(by_flag["method"], "control");
  EXPECT_EQ(by_flag["seed"], "");
  EXPECT_TRUE(MentionsFlag("`--max_step_m`", "max_step_m"));
  EXPECT_FALSE(MentionsFlag("`--max_step_m`", "max_step"));
  EXPECT_FALSE(MentionsFlag("`--models_dir`", "model"));
}

TEST(CliDocs, GlobalInvocationsAreDocumented) {
  const std::string doc = ReadDoc("cli.md");
  for (const char* text : {"ccma --help", "ccma COMMAND --help", "ccma --version"}) {
    EXPECT_NE(doc.find(text), std::string::npos) << text;
  }
}

// ---- (c): JSON keys ---------------------------------------------------------
// Every key each command prints, nested ones included, is in that command's
// key tables: tests/cli_json_keys_test.py (the CTest cli_json_keys), and the
// help texts shown are the tool's own: scripts/update_cli_docs.py --check
// (cli_docs_generated).

// ---- (d): model format keys -----------------------------------------------

TEST(ModelFormatDocs, EveryLoaderKeyIsDocumented) {
  // The known-key lists of formats/internal/model_*.cc (CheckKeys calls).
  const std::vector<std::string> keys = {
      // top level
      "name", "description", "bodies", "mobile_bases", "joints", "end_effector",
      // bodies
      "position", "rpy",
      // mobile_bases
      "type", "actuation", "pose", "wheels",
      // wheels
      "angle", "distance", "radius", "mounting", "roller", "track",
      // joints
      "between", "point", "axis", "axes", "actuated", "limits", "world",
      // end_effector
      "body", "controlled",
      // collision, obstacles
      "collision", "margin", "base_radius", "base_height", "links", "from", "to", "ignore", "obstacles",
      "cylinder", "box", "center", "height", "size", "yaw",
      // masses and loads
      "mass", "com", "payload", "gravity", "effort_limits", "push_limit",
      // compliance
      "stiffness", "translation", "rotation"};
  const std::string doc = ReadDoc("model_format.md");
  for (const std::string& key : keys) {
    EXPECT_NE(doc.find("`" + key + "`"), std::string::npos)
        << "docs/model_format.md does not name the model key `" << key << "`";
  }
}

TEST(DocsIndex, LinksTheCommandLineReference) {
  EXPECT_NE(ReadDoc("README.md").find("(cli.md)"), std::string::npos);
}

// ---- (e): README.md and docs/ against the repository ------------------------

struct Page {
  std::string name;    // for messages: README.md, docs/NAME.md
  std::string text;
  std::string folder;  // where its relative links point from (in the source tree)
};

// README.md and every docs/*.md (from DocsDir(), so an edited copy is checked).
std::vector<Page> Pages() {
  const std::string source = CCMA_SOURCE_DIR;
  std::vector<Page> pages = {{"README.md", Slurp(source + "/README.md"), source}};
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(DocsDir())) {
    if (entry.path().extension() == ".md") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) pages.push_back({"docs/" + name, Slurp(DocsDir() + "/" + name), source + "/docs"});
  return pages;
}

int LineOf(const std::string& text, size_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

bool IsPathChar(char c) { return IsWordChar(c) || c == '.' || c == '/' || c == '*' || c == '-'; }

// The repository's top-level folders (build trees aside: they hold outputs).
std::vector<std::string> TopLevelFolders() {
  std::vector<std::string> folders;
  for (const auto& entry : std::filesystem::directory_iterator(CCMA_SOURCE_DIR)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name[0] != '.' && name.rfind("build", 0) != 0) folders.push_back(name);
  }
  return folders;
}

struct PathMention {
  std::string path;  // relative to the repository root
  int line;
};

// Repository paths in `text`: words that start with a top-level folder and a
// slash (`scripts/demo.sh`, `models/*.yaml`, `docs/`), outside other paths
// (`$HOME/ccma/lib` is none). Left out: placeholders (`view_<name>.png`,
// `{png,svg}`) and what a command writes (`--out=...`, `--plot=...`).
std::vector<PathMention> RepositoryPaths(const std::string& text, const std::vector<std::string>& folders) {
  std::vector<PathMention> mentions;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i > 0 && IsPathChar(text[i - 1])) continue;
    bool starts = false;
    for (const std::string& f : folders) starts = starts || text.compare(i, f.size() + 1, f + "/") == 0;
    if (!starts) continue;
    size_t end = i;
    while (end < text.size() && IsPathChar(text[end])) ++end;
    const bool placeholder = end < text.size() && (text[end] == '<' || text[end] == '{');
    const bool output = (i >= 4 && text.compare(i - 4, 4, "out=") == 0) || (i >= 5 && text.compare(i - 5, 5, "plot=") == 0);
    std::string path = text.substr(i, end - i);
    while (!path.empty() && (path.back() == '.' || path.back() == '-')) path.pop_back();
    if (!placeholder && !output) mentions.push_back({path, LineOf(text, i)});
    i = end;
  }
  return mentions;
}

// Targets of Markdown links and images, `[...](TARGET)`, other than web
// addresses and anchors within the page; the anchor of TARGET#anchor dropped.
std::vector<PathMention> LinkTargets(const std::string& text) {
  std::vector<PathMention> links;
  for (size_t p = text.find("]("); p != std::string::npos; p = text.find("](", p + 2)) {
    const size_t end = text.find(')', p + 2);
    if (end == std::string::npos) break;
    std::string target = text.substr(p + 2, end - p - 2);
    target = target.substr(0, target.find('#'));
    if (target.empty() || target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
    links.push_back({target, LineOf(text, p)});
  }
  return links;
}

// A file or folder (a trailing slash: a folder), or a pattern with `*` that
// matches at least one.
bool Exists(const std::string& path) {
  if (path.find('*') != std::string::npos) {
    glob_t matches;
    const bool found = glob(path.c_str(), 0, nullptr, &matches) == 0 && matches.gl_pathc > 0;
    globfree(&matches);
    return found;
  }
  if (!path.empty() && path.back() == '/') return std::filesystem::is_directory(path);
  return std::filesystem::exists(path);
}

TEST(RepositoryDocs, NameOnlyFilesThatExist) {
  const std::vector<std::string> folders = TopLevelFolders();
  int checked = 0;
  for (const Page& page : Pages()) {
    for (const PathMention& m : RepositoryPaths(page.text, folders)) {
      ++checked;
      // docs/python.md also names files of the Python package as Python
      // sees them (`ccma/_ccma.pyi` is python/ccma/_ccma.pyi).
      const bool found = Exists(std::string(CCMA_SOURCE_DIR) + "/" + m.path) ||
                         (page.name == "docs/python.md" && Exists(std::string(CCMA_SOURCE_DIR) + "/python/" + m.path));
      EXPECT_TRUE(found) << page.name << ":" << m.line << ": names " << m.path << ", which is not in the repository";
    }
    for (const PathMention& m : LinkTargets(page.text)) {
      ++checked;
      EXPECT_TRUE(Exists(page.folder + "/" + m.path))
          << page.name << ":" << m.line << ": links to " << m.path << ", which is not in the repository";
    }
  }
  EXPECT_GT(checked, 200);
}

// The extraction rules themselves, on a small page.
TEST(RepositoryDocs, PathMentionsAreFound) {
  const std::string text =
      "Run `scripts/demo.sh`, see models/*.yaml and docs/.\n"
      "$HOME/ccma/lib stays; --out=models/new.yaml and docs/images/view_<name>.png too;\n"
      "[cli](cli.md#ccma-view) [web](https://example.org/x.md) [here](#top) ![i](images/a.png)";
  std::vector<std::string> paths, links;
  for (const PathMention& m : RepositoryPaths(text, {"scripts", "models", "docs", "ccma"})) paths.push_back(m.path);
  for (const PathMention& m : LinkTargets(text)) links.push_back(m.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"scripts/demo.sh", "models/*.yaml", "docs/"}));
  EXPECT_EQ(links, (std::vector<std::string>{"cli.md", "images/a.png"}));
  EXPECT_TRUE(Exists(std::string(CCMA_SOURCE_DIR) + "/models/*.yaml"));
  EXPECT_FALSE(Exists(std::string(CCMA_SOURCE_DIR) + "/models/*.yml"));
  EXPECT_FALSE(Exists(std::string(CCMA_SOURCE_DIR) + "/README.md/"));
}

// Measured runs, with their dates and machines, live in benchmarks/RESULTS.md.
TEST(RepositoryDocs, CarryNoDatesOrHistory) {
  auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  for (const Page& page : Pages()) {
    for (size_t i = 0; i + 10 <= page.text.size(); ++i) {
      const std::string s = page.text.substr(i, 10);  // YYYY-MM-DD
      const bool date = (s.compare(0, 2, "19") == 0 || s.compare(0, 2, "20") == 0) && digit(s[2]) && digit(s[3]) &&
                        s[4] == '-' && digit(s[5]) && digit(s[6]) && s[7] == '-' && digit(s[8]) && digit(s[9]);
      EXPECT_FALSE(date) << page.name << ":" << LineOf(page.text, i) << ": a date, " << s;
    }
    std::string lower = page.text;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* phrase : {"this session", "previous session", "earlier session", "last session"}) {
      const size_t p = lower.find(phrase);
      EXPECT_EQ(p, std::string::npos) << page.name << ":" << LineOf(page.text, p) << ": \"" << phrase << "\"";
    }
  }
}

TEST(Readme, IsAFrontDoor) {
  const std::string readme = Slurp(std::string(CCMA_SOURCE_DIR) + "/README.md");
  EXPECT_LE(Lines(readme).size(), 200u);
  // The two commands, on its first screen (40 lines).
  std::string first_screen;
  for (size_t i = 0; i < std::min<size_t>(40, Lines(readme).size()); ++i) first_screen += Lines(readme)[i] + "\n";
  EXPECT_NE(first_screen.find("scripts/demo.sh"), std::string::npos);
  EXPECT_NE(first_screen.find("scripts/test.sh"), std::string::npos);
  // A table row for every command the tool lists, and none for another.
  for (const std::string& c : Facts().commands) {
    EXPECT_NE(readme.find("| `ccma " + c + "` |"), std::string::npos) << "the README's table lacks ccma " << c;
  }
  for (const std::string& line : Lines(readme)) {
    if (line.rfind("| `ccma ", 0) != 0) continue;
    const std::string name = line.substr(8, line.find('`', 8) - 8);
    EXPECT_EQ(std::count(Facts().commands.begin(), Facts().commands.end(), name), 1) << line;
  }
  EXPECT_NE(readme.find("(docs/architecture.md)"), std::string::npos);
  EXPECT_NE(ReadDoc("README.md").find("(architecture.md)"), std::string::npos);
}

// The code of a ```cpp block (comments and indentation dropped, blank lines skipped).
std::vector<std::string> CodeLines(const std::vector<std::string>& lines) {
  std::vector<std::string> code;
  for (std::string line : lines) {
    line = line.substr(0, line.find("//"));
    const size_t first = line.find_first_not_of(" \t"), last = line.find_last_not_of(" \t");
    if (first != std::string::npos) code.push_back(line.substr(first, last - first + 1));
  }
  return code;
}

// The README's and docs/cpp.md's C++ examples are excerpts of
// apps/embed_example.cc, which the tests build and run: every code line is
// there, in the same order.
TEST(Readme, CppExampleIsTakenFromEmbedExample) {
  const std::vector<std::string> program =
      CodeLines(Lines(Slurp(std::string(CCMA_SOURCE_DIR) + "/apps/embed_example.cc")));
  ASSERT_GT(program.size(), 20u);
  for (const Page& page : Pages()) {
    if (page.name != "README.md" && page.name != "docs/cpp.md") continue;
    std::vector<std::string> block;
    bool in_cpp = false;
    int blocks = 0;
    for (const std::string& line : Lines(page.text)) {
      if (IsFence(line)) {
        if (!in_cpp && line.find("```cpp") != std::string::npos) ++blocks;
        in_cpp = !in_cpp && line.find("```cpp") != std::string::npos;
        continue;
      }
      if (in_cpp) block.push_back(line);
    }
    EXPECT_EQ(blocks, 1) << page.name;
    if (page.name == "README.md") EXPECT_LE(block.size(), 20u);
    const std::vector<std::string> code = CodeLines(block);
    EXPECT_GT(code.size(), 10u) << page.name;
    size_t at = 0;
    for (const std::string& line : code) {
      const auto found = std::find(program.begin() + static_cast<std::ptrdiff_t>(at), program.end(), line);
      EXPECT_NE(found, program.end()) << page.name << ": `" << line
                                      << "` is not in apps/embed_example.cc (after the lines before it)";
      if (found != program.end()) at = static_cast<size_t>(found - program.begin()) + 1;
    }
  }
}

}  // namespace
