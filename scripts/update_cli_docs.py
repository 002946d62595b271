#!/usr/bin/env python3
"""Writes the tool's own help text into docs/cli.md, or checks that it is there.

  scripts/update_cli_docs.py [--tool=build/apps/ccma] [--doc=docs/cli.md]          rewrite the blocks
  scripts/update_cli_docs.py --check [--tool=...] [--doc=...]                      exit 1 if one differs
  scripts/update_cli_docs.py --self-test                                           the block rules, on a small page

A generated block in docs/cli.md is a marker line, a fenced code block and an
end line:

  <!-- generated from: ccma --help -->                 the whole `ccma --help`
  <!-- generated from: ccma export --help -->          the whole `ccma export --help`
  <!-- generated from: ccma check --help, usage -->     its synopsis only (the lines after
                                                        "usage: " up to the first blank line)
  ```
  ...the tool's output...
  ```
  <!-- end generated -->

Whatever lies between a marker and its end line is replaced. `--check` (the
CTest `cli_docs_generated`) also requires the `ccma --help` block and, in the
section of every command `ccma --help` lists (the `## \\`ccma NAME\\`` heading),
that command's usage block.
"""
import argparse
import difflib
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MARKER = re.compile(r"^<!-- generated from: ccma((?: [a-z]+)?) --help(, usage)? -->$")
END = "<!-- end generated -->"


class DocError(Exception):
    pass


def tool_output(tool, command):
    """`ccma [COMMAND] --help` on stdout; DocError unless it exits 0."""
    args = [tool] + ([command] if command else []) + ["--help"]
    run = subprocess.run(args, capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        raise DocError(f"`{' '.join(args)}` exited {run.returncode}: {run.stderr.strip()}")
    return run.stdout


def usage_of(help_text):
    """The synopsis of a command's help: from "usage: " to the first blank line, without "usage: "."""
    lines = help_text.split("\n")
    if not lines or not lines[0].startswith("usage: "):
        raise DocError("the help does not start with 'usage: ':\n" + help_text[:200])
    out = [lines[0][len("usage: "):]]
    for line in lines[1:]:  # indented under the first line's "ccma": as far less here
        if not line.strip():
            break
        out.append(line[len("usage: "):] if line.startswith(" " * len("usage: ")) else line)
    return "\n".join(out) + "\n"


def blocks(lines):
    """(start, end, command, usage) of every generated block: lines[start] is the marker, lines[end] the end line."""
    found = []
    i = 0
    while i < len(lines):
        m = MARKER.match(lines[i])
        if m:
            try:
                end = lines.index(END, i + 1)
            except ValueError:
                raise DocError(f"line {i + 1}: '{lines[i]}' has no '{END}' after it")
            nested = [k for k in range(i + 1, end) if MARKER.match(lines[k])]
            if nested:
                raise DocError(f"line {nested[0] + 1}: a marker inside the block of line {i + 1}")
            found.append((i, end, m.group(1).strip(), bool(m.group(2))))
            i = end
        i += 1
    return found


def command_sections(lines):
    """{command: (first line, last line)} of the `## \\`ccma NAME\\`` sections: from the heading to the line
    before the next heading of level 1 or 2 (headings inside code blocks do not count)."""
    heads, in_code = [], False
    for n, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            in_code = not in_code
        elif not in_code and (line.startswith("# ") or line.startswith("## ")):
            heads.append(n)
    sections = {}
    for k, n in enumerate(heads):
        m = re.match(r"^## `ccma ([a-z]+)`", lines[n])
        if m and m.group(1) not in sections:
            sections[m.group(1)] = (n, heads[k + 1] - 1 if k + 1 < len(heads) else len(lines) - 1)
    return sections


def generate(doc_text, help_of):
    """The page with every block rewritten from help_of(command) ('' for the global help)."""
    lines = doc_text.split("\n")
    out, last = [], 0
    for start, end, command, usage in blocks(lines):
        text = help_of(command)
        if usage:
            text = usage_of(text)
        if not text.endswith("\n"):
            text += "\n"
        out += lines[last:start + 1] + ["```"] + text[:-1].split("\n") + ["```"]
        last = end
    out += lines[last:]
    return "\n".join(out)


def missing_blocks(doc_text, commands):
    """Blocks that --check requires and the page lacks, as messages."""
    lines = doc_text.split("\n")
    found = blocks(lines)
    problems = []
    if not any(c == "" and not u for _, _, c, u in found):
        problems.append("no '<!-- generated from: ccma --help -->' block")
    sections = command_sections(lines)
    for command in commands:
        if command not in sections:
            problems.append(f"no '## `ccma {command}`' section")
            continue
        first, last = sections[command]
        if not any(c == command and u and first <= s <= last for s, _, c, u in found):
            problems.append(f"the section of ccma {command} has no '<!-- generated from: ccma {command} --help, "
                            f"usage -->' block (its synopsis)")
    return problems


def listed_commands(global_help):
    return re.findall(r"^  ccma ([a-z]+) ", global_help, re.M)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tool", default=os.path.join(ROOT, "build", "apps", "ccma"))
    parser.add_argument("--doc", default=os.path.join(ROOT, "docs", "cli.md"))
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args(argv)
    if args.self_test:
        return self_test()
    cache = {}

    def help_of(command):
        if command not in cache:
            cache[command] = tool_output(args.tool, command)
        return cache[command]

    with open(args.doc, encoding="utf-8") as f:
        doc = f.read()
    try:
        new = generate(doc, help_of)
        problems = missing_blocks(new, listed_commands(help_of("")))
    except DocError as e:
        print(f"{args.doc}: {e}", file=sys.stderr)
        return 1
    if args.check:
        if new != doc:
            diff = difflib.unified_diff(doc.split("\n"), new.split("\n"), args.doc, "from " + args.tool, lineterm="")
            print("\n".join(diff), file=sys.stderr)
            print(f"{args.doc}: the generated blocks differ from the tool's help (above); "
                  "run scripts/update_cli_docs.py", file=sys.stderr)
        for p in problems:
            print(f"{args.doc}: {p}", file=sys.stderr)
        return 1 if new != doc or problems else 0
    if new != doc:
        with open(args.doc, "w", encoding="utf-8") as f:
            f.write(new)
    for p in problems:
        print(f"{args.doc}: {p}", file=sys.stderr)
    return 1 if problems else 0


def self_test():
    page = "\n".join([
        "# Title", "## `ccma check`", "<!-- generated from: ccma check --help, usage -->", "```", "old", "```",
        END, "text", "## Other", "<!-- generated from: ccma --help -->", END, ""])
    helps = {"": "  ccma check  validate\n", "check": "usage: ccma check --model=FILE\n             [--x]\n\nWhat it does.\n"}
    new = generate(page, helps.__getitem__)
    assert "```\nccma check --model=FILE\n      [--x]\n```\n" + END in new, new
    assert "<!-- generated from: ccma --help -->\n```\n  ccma check  validate\n```\n" + END in new, new
    assert generate(new, helps.__getitem__) == new  # a second run changes nothing
    assert missing_blocks(new, ["check"]) == []
    assert len(missing_blocks(new, ["check", "view"])) == 1
    moved = new.replace("## Other", "## `ccma view`").replace("## `ccma check`", "## Check")
    assert any("ccma check" in p for p in missing_blocks(moved, ["check"]))
    for broken in ["<!-- generated from: ccma --help -->\ntext", "<!-- generated from: ccma --help -->\n"
                   "<!-- generated from: ccma check --help -->\n" + END]:
        try:
            blocks(broken.split("\n"))
            raise AssertionError("accepted: " + broken)
        except DocError:
            pass
    print("update_cli_docs self-test: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
