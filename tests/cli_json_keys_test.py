#!/usr/bin/env python3
"""Every JSON key a `ccma` command prints is documented in that command's section of docs/cli.md.

  CCMA_TOOL=build/apps/ccma python3 tests/cli_json_keys_test.py [-v] [-k NAME]   (the CTest cli_json_keys)

Each command runs on the bundled models with the options that add keys
(obstacles, masses and limits, a store, plots, failures that add `warning`),
and every key of its JSON, nested objects and the objects in arrays included,
must be documented in the **key tables** of the command's section (from the
`## \\`ccma NAME\\`` heading to the next heading of level 1 or 2):

- a key table is a Markdown table whose header's first cell is `key`;
- a top-level key is documented by a row whose first cell names it in
  backticks (`` `model` ``, or several: `` `model`, `method` ``);
- a nested key `a.b` (b in the object a, or in the objects of the list a) is
  documented by a row whose first cell names `` `a.b` ``, or by the row that
  documents `a` when that row names `` `b` `` in backticks anywhere in it;
  deeper keys the same way (`a.b.c`: a row naming `a.b.c`, or `c` in a row
  that documents `a.b`); a row naming `a.b` documents `a` too.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOOL = os.environ.get("CCMA_TOOL", os.path.join(ROOT, "build", "apps", "ccma"))
DOC = os.environ.get("CCMA_CLI_DOC", os.path.join(ROOT, "docs", "cli.md"))
IDENT = r"[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*"


# ---- docs/cli.md ---------------------------------------------------------------------------------

class Row:
    def __init__(self, cells, line):
        self.line = line
        self.names = set(_names(cells[0]))
        self.mentions = set()
        for name in _names(" | ".join(cells)):
            self.mentions.add(name)
            self.mentions.update(name.split("."))


def _names(text):
    """The identifiers inside the backtick spans of `text` (`a.b` kept whole)."""
    return [n for span in re.findall(r"`([^`]*)`", text) for n in re.findall(IDENT, span)]


def _cells(line):
    """The cells of a table row, split at '|' but not at '\\|'."""
    cells = re.split(r"(?<!\\)\|", line.strip())
    return [c.strip() for c in cells[1:-1]] if len(cells) > 2 else []


def key_rows(doc_text):
    """{command: [Row]} from the key tables of each command's section."""
    lines = doc_text.split("\n")
    rows, command, in_code, table = {}, None, False, None
    for n, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
            continue
        if in_code:
            continue
        if line.startswith("# ") or line.startswith("## "):
            m = re.match(r"^## `ccma ([a-z]+)`", line)
            command = m.group(1) if m else None
            if command:
                rows.setdefault(command, [])
        if not line.startswith("|"):
            table = None
            continue
        cells = _cells(line)
        if table is None:  # a header
            table = "key" if cells and cells[0] == "key" else "other"
        elif command and table == "key" and not re.match(r"^\|[\s|:-]+\|$", line.strip()):
            rows[command].append(Row(cells, n))
    return rows


def documenting_rows(rows, path):
    """The rows that document the key path (a tuple of names); empty when it is not documented."""
    name = ".".join(path)
    found = [r for r in rows if name in r.names or any(n.startswith(name + ".") for n in r.names)]
    if len(path) > 1:
        found += [r for r in documenting_rows(rows, path[:-1]) if path[-1] in r.mentions]
    return found


def key_paths(value, prefix=()):
    """Every key path of a JSON value: the keys of objects, through lists (a list adds no name)."""
    if isinstance(value, dict):
        for key, inner in value.items():
            yield prefix + (key,)
            yield from key_paths(inner, prefix + (key,))
    elif isinstance(value, list):
        for inner in value:
            yield from key_paths(inner, prefix)


# ---- the runs ---------------------------------------------------------------------------------

def model(name):
    return f"--model={ROOT}/models/{name}.yaml"


def example(path):
    return f"{ROOT}/examples/{path}"


# Put last in a run's arguments: the run gets a PATH without gnuplot (the keys of missing plots).
NO_GNUPLOT = "<no gnuplot>"

REDUCED_HOME = ("0,0.583012702,1.570796327,-0.504903811,-0.291506351,-2.617993878,0.504903811,-0.291506351,"
                "-0.523598776")


def write(tmp, name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def fixtures(tmp):
    """Input files the runs share, written into tmp."""
    with open(example("my_first_mechanism.yaml")) as mechanism:
        first = mechanism.read()
    f = {
        # Not rigid with its controls fixed: the walkthrough model with spherical joints for revolute ones.
        "ss_legs": write(tmp, "ss_legs.yaml", first.replace("type: revolute,", "type: spherical,")),
        # A waypoint beyond the legs' reach (z = 0.9 m).
        "far": write(tmp, "far.csv", "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n1,0,0,0.9,0,0,0\n"),
        # A short path whose chain tears with 1 s of latency.
        "lift": write(tmp, "lift.csv", "time,x,y,z,roll,pitch,yaw\n0,0,0,0.6,0,0,0\n5,0,0.08,0.6,0,0,0\n"
                                       "10,0,-0.08,0.6,0,0,0\n"),
        # A pillar beside the 4dof end-effector's path.
        "pillar": write(tmp, "pillar.yaml", "obstacles:\n  - {name: pillar, cylinder: {center: [0.0, 0.0], "
                                            "radius: 0.05, height: 0.3}}\n"),
    }
    return f


def runs(tmp, f):
    """(command, args) of every run; outputs go to tmp."""
    o = lambda name: f"--out={tmp}/{name}"
    seq = f"--waypoints={ROOT}/models/paths/4dof_sequential.csv"
    robots = f"{ROOT}/models/robots/example-parallel-robots"
    far = REDUCED_HOME.replace("0.583012702", "1.2")
    return [
        ("check", [model("4dof_reduced")]),
        ("check", ["--model=" + f["ss_legs"]]),
        ("check", [model("4dof_reduced"), "--obstacles=" + f["pillar"]]),
        ("simulate", [model("4dof_reduced")]),
        ("simulate", [model("4dof_reduced"), "--controls=" + far]),
        ("simulate", [model("stewart_gough_6ups")]),
        ("simulate", [model("4dof_reduced"), "--obstacles=" + f["pillar"]]),
        ("control", [model("4dof_reduced"), "--target=0.02,0.01,0.62,0,0,0.05"]),
        ("control", [model("4dof_reduced"), "--target=0,0,0.9,0"]),
        ("control", [model("6dof_six_agents"), "--target=0.01,0,0.6,0,0,0", "--singularity_weight=1",
                     "--pivot_weight=1", "--secondary=spread"]),
        ("control", [model("4dof_reduced"), "--target=0.1,0,0.6,0", "--obstacles=" + f["pillar"]]),
        ("control", ["--model=" + example("statics/4dof_payload.yaml"), "--target=0,0,0.65,0"]),
        ("trajectory", [model("4dof_reduced"), seq, o("seq.csv")]),
        ("dynamics", [model("4dof_reduced"), f"--trajectory={tmp}/seq.csv", o("seq_dynamics.csv")]),
        ("trajectory", ["--model=" + example("dynamics/4dof_payload.yaml"), seq, o("payload_seq.csv")]),
        ("retime", ["--model=" + example("dynamics/4dof_payload.yaml"), f"--trajectory={tmp}/payload_seq.csv",
                    o("payload_fast.csv")]),
        ("trajectory", [model("4dof_reduced"), "--waypoints=" + f["far"], o("far_out.csv"), "--secondary=travel"]),
        ("trajectory", [model("4dof_reduced"), seq, o("pillar.csv"), "--obstacles=" + f["pillar"]]),
        ("plan", ["--model=" + example("obstacles/pillar_detour.yaml"),
                  "--waypoints=" + example("obstacles/one_metre_x.csv"), o("plan.csv")]),
        ("plan", [model("4dof_reduced"), "--waypoints=" + f["far"], o("plan_far.csv"), "--plan_iterations=2"]),
        ("statics", ["--model=" + example("statics/4dof_payload.yaml")]),
        ("statics", ["--model=" + example("statics/stewart_gough_loaded.yaml"), "--wrench=0,0,-2000,0,0,0"]),
        ("statics", ["--model=" + example("statics/tripod.yaml")]),
        ("statics", ["--model=" + example("statics/stewart_gough_compliant.yaml"), "--wrench=0,0,-100,0,0,0"]),
        ("statics", ["--model=" + example("statics/4dof_payload.yaml"), "--obstacles=" + f["pillar"]]),
        ("generate", ["--agents=4", o("four.yaml")]),
        ("generate", ["--agents=6", "--kind=stewart_gough", o("sg.yaml")]),
        ("import", [f"--from={robots}/robot_delta/robot.urdf", f"--closures={robots}/robot_delta/robot.yaml",
                    "--end_effector=eff", o("delta.yaml")]),
        ("import", [f"--from={ROOT}/models/robots/four_bar_loop.sdf", "--actuated=crank",
                    "--end_effector=coupler:2.4,0,0", o("four_bar.yaml")]),
        ("export", [model("hybrid_ccma"), "--format=urdf", o("hybrid.urdf")]),
        ("export", [model("hybrid_ccma"), "--format=sdf", o("hybrid.sdf")]),
        ("bench", [model("4dof_reduced"), "--steps=1", f"--out={tmp}/bench"]),
        ("bench", ["--scaling", "--steps=1"]),
        ("replay", [model("4dof_reduced"), "--waypoints=" + f["lift"], f"--out={tmp}/replay", "--latency_s=1"]),
        ("replay", [model("4dof_reduced"), "--waypoints=" + f["far"], f"--out={tmp}/replay_far", NO_GNUPLOT]),
        ("workspace", [model("4dof_reduced"), o("ws.csv"), "--x=-0.2:0.2", "--z=0.5:0.9", "--resolution=4",
                       f"--store={tmp}/store", f"--plot={tmp}/plots"]),
        ("workspace", [model("4dof_reduced"), o("random.csv"), "--z=0.5:0.9", "--samples=5", f"--plot={tmp}/p2",
                       NO_GNUPLOT]),
        ("view", [model("4dof_reduced"), o("model.html"), "--meshes", "--color_by=load"]),
        ("view", [model("4dof_reduced"), f"--trajectory={tmp}/pillar.csv", "--obstacles=" + f["pillar"],
                  o("path.html")]),
        ("view", [model("4dof_reduced"), f"--replay={tmp}/replay", o("replay.html")]),
        ("view", [f"--model={ROOT}/tests/meshes/four_bar_meshes.yaml", "--meshes", o("meshes.html")]),
        ("view", [model("4dof_reduced"), f"--workspace={tmp}/ws.csv", o("ws.html")]),
        ("view", ["--model=" + example("statics/stewart_gough_compliant.yaml"), "--deflection=100",
                  "--controls=0.01,0,0,0,0,0", "--wrench=0,0,-50,0,0,0", o("sag.html")]),
        ("design", [model("4dof_reduced"), f"--targets={ROOT}/models/targets/4dof_high_z.csv", o("high.yaml"),
                    "--vary_length=joint0:joint1,joint3:joint4,joint6:joint7"]),
        ("design", ["--model=" + example("statics/4dof_payload.yaml"),
                    "--targets=" + example("statics/4dof_payload_targets.csv"), o("payload.yaml"),
                    "--vary=joint1.point", "--objective=payload", "--design_iterations=2"]),
        ("design", [model("4dof_reduced"), f"--targets={ROOT}/models/targets/4dof_high_z.csv", o("never.yaml"),
                    "--vary=joint1.z", "--min_singular_value=100", "--design_iterations=1"]),
    ]


# ---- the test ---------------------------------------------------------------------------------

def undocumented(rows, document):
    """The key paths of `document` that `rows` do not document, in first-seen order."""
    missing = []
    for path in key_paths(document):
        if path not in missing and not documenting_rows(rows, path):
            missing.append(path)
    return missing


def missing_message(command, path):
    """What to add to docs/cli.md for an undocumented key path."""
    name = ".".join(path)
    fix = f"add a row naming `{path[0]}`" if len(path) == 1 else \
        f"name `{path[-1]}` in the row of `{'.'.join(path[:-1])}` (or add a row naming `{name}`)"
    return f"docs/cli.md, section `ccma {command}`: the key `{name}` is not in its key tables; {fix}"


class CliJsonKeys(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(DOC, encoding="utf-8") as f:
            cls.rows = key_rows(f.read())
        cls.tmp = tempfile.mkdtemp(prefix="cli_json_keys_")
        cls.fixtures = fixtures(cls.tmp)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_every_printed_key_is_in_its_commands_key_tables(self):
        seen_commands = set()
        for command, args in runs(self.tmp, self.fixtures):
            seen_commands.add(command)
            line = " ".join(["ccma", command] + args)
            with self.subTest(run=line):
                env = dict(os.environ)
                if args[-1:] == [NO_GNUPLOT]:
                    args, env["PATH"] = args[:-1], self.tmp  # a folder without gnuplot
                    line = line[:-len(NO_GNUPLOT)] + "(PATH without gnuplot)"
                run = subprocess.run([TOOL, command] + args, capture_output=True, text=True, timeout=600, env=env)
                self.assertEqual(run.returncode, 0, f"{line}\n{run.stderr}")
                document = json.loads(run.stdout)
                rows = self.rows.get(command)
                self.assertTrue(rows, f"docs/cli.md: the section '## `ccma {command}`' has no key table "
                                      "(a table whose header's first cell is `key`)")
                missing = undocumented(rows, document)
                if missing:
                    self.fail("\n".join([missing_message(command, p) for p in missing] + [f"(printed by: {line})"]))
        listed = re.findall(r"^  ccma ([a-z]+) ", subprocess.run([TOOL, "--help"], capture_output=True,
                                                                text=True).stdout, re.M)
        self.assertEqual(sorted(set(listed) - seen_commands), [], "commands this test does not run")

    def test_the_convention_on_a_small_page(self):
        page = "\n".join([
            "## `ccma check`", "| key | type | meaning |", "|---|---|---|",
            "| `model`, `bodies` | x | the `name` |", "| `clearance` | object | `min`, `pair` |",
            "| `a.b` | object | with `c` |", "| (efforts) | – | `effort` |",
            "", "| column | meaning |", "|---|---|", "| `x_m` | m |",
            "```", "| `inside` | code |", "```",
            "## `ccma simulate`", "| key | meaning |", "|---|---|", "| `converged` | `a \\| b` |", "## Other",
            "| key | meaning |", "|---|---|", "| `elsewhere` | |"])
        rows = key_rows(page)
        self.assertEqual(sorted(rows), ["check", "simulate"])
        doc = {"model": "m", "bodies": [{"name": "b"}], "clearance": {"min": 1, "pair": [], "margin": 0},
               "a": {"b": {"c": 1, "d": 2}}, "x_m": 0, "inside": 0, "converged": True, "effort": 0}
        self.assertEqual(undocumented(rows["check"], doc),
                         [("clearance", "margin"), ("a", "b", "d"), ("x_m",), ("inside",), ("converged",),
                          ("effort",)])
        self.assertEqual(undocumented(rows["simulate"], {"converged": 1, "elsewhere": 2}), [("elsewhere",)])
        self.assertEqual(list(key_paths([{"k": [{"j": 1}]}])), [("k",), ("k", "j")])


if __name__ == "__main__":
    unittest.main()
