"""Workspace sampling speed: wall time of ccma.workspace on one thread, on two threads and
on a 2-worker Dask LocalCluster (processes, one thread each), same map, in the same run;
medians of REPS runs. Writes its section of benchmarks/RESULTS.md to
benchmarks/results/workspace.md, which scripts/results.sh puts into RESULTS.md.

    PYTHONPATH=build/python python3 benchmarks/workspace_bench.py [--large]

--large adds the 100,000-sample map (resolution 316), once each, two threads against Dask.
"""
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

import numpy as np

import ccma

ROOT = pathlib.Path(__file__).resolve().parents[1]
MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
RANGES = {"x": (-0.4, 0.4), "z": (0.3, 1.2)}  # the legs reach z = 0.85 m: about 60 % reachable
REPS = 5


def same(a, b):
    return all(np.array_equal(a[k], b[k]) for k in ("reachable", "controls", "start", "wave", "sigma_min"))


def measure(resolution, reps, client, with_one_thread):
    """Rows (name, median seconds) for one map, the runs interleaved (rep 1 of each, then
    rep 2, ...) so that the machine's noise falls on all of them; checks that every run
    gives the same map."""
    runs = [("1 thread", dict(threads=1))] if with_one_thread else []
    runs += [("2 threads", dict(threads=2)), ("Dask LocalCluster, 2 worker processes x 1 thread", dict(client=client))]
    times, maps = {name: [] for name, _ in runs}, []
    for _ in range(reps):
        for name, kw in runs:
            start = time.perf_counter()
            maps.append(ccma.workspace(MODEL, RANGES, resolution=resolution, **kw))
            times[name].append(time.perf_counter() - start)
    assert all(same(maps[0], m) for m in maps[1:]), "the runs gave different maps"
    return [(name, statistics.median(times[name])) for name, _ in runs], maps[0]


# Measured once, not by this script: the tiled maps against the global wave continuation
# (the algorithm before tiles, build of commit b495ac8), one thread each.
REACHABILITY = """Reachable samples, tiled (default tile size) against the global wave continuation that \
preceded tiles (measured once, 2026-12-02, with a build of commit b495ac8; a map of one tile, \
`tile_size` >= `resolution`, is that continuation):

| model, map | samples | global continuation | tiled | samples that differ |
|---|---|---|---|---|
| 4dof_reduced, x [-0.4, 0.4] x z [0.3, 1.2], resolution 100 | 10,000 | 6,050 | 6,050 | 0 |
| 4dof_reduced, x [-0.4, 0.4] x y [-0.4, 0.4] x z [0.3, 1.2], resolution 20 | 8,000 | 4,744 | 4,744 | 0 |
| 4dof_reduced, x [-0.4, 0.4] x z [0.3, 1.2], 4,000 draws (seed 5) | 4,000 | 2,431 | 2,432 | 3 |
| 6dof_six_agents, x [-0.4, 0.4] x z [0.3, 1.2], resolution 60 | 3,600 | 2,380 | 2,380 | 0 |
| 6dof_six_agents, x [-0.3, 0.3] x y [-0.3, 0.3] x z [0.4, 1.0], resolution 16 | 4,096 | 3,584 | 3,584 | 0 |
| 6dof_six_agents, x [-0.3, 0.3] x yaw [-1, 1], resolution 60 | 3,600 | 3,600 | 3,600 | 0 |

The grids are identical sample for sample. The three draws that differ lie at z = 0.342 to 0.353 m, \
the band where 4dof_reduced's links pass horizontal (dG/ds singular) and whether a walk gets through \
depends on where it starts; draws have no adjacent cells, and there a tile started them from the \
nearest reached draw it sees rather than the nearest in the whole map (one lost, two gained)."""


def machine():
    cpu = "unknown"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()}"


def table(resolution, rows, m, reps):
    n, reach = len(m["reachable"]), int(m["reachable"].sum())
    text = [f"**{n:,} samples** (resolution {resolution}, {m['tiles']} tiles of 16 x 16 cells, {reach:,} reachable), "
            f"{'median of %d interleaved runs' % reps if reps > 1 else 'one run'} each:", "",
            "| run | seconds | samples/s | speed-up over 1 thread | time / 2 threads |", "|---|---|---|---|---|"]
    one = dict(rows).get("1 thread")
    two = dict(rows)["2 threads"]
    for name, seconds in rows:
        speed = f"{one / seconds:.2f}x" if one else "–"
        text.append(f"| {name} | {seconds:.2f} | {n / seconds:.0f} | {speed} | {seconds / two:.2f} |")
    return text + [""]


def main():
    import distributed
    large = "--large" in sys.argv[1:]
    date = subprocess.run(["date", "-u", "+%Y-%m-%d %H:%M UTC"], capture_output=True, text=True).stdout.strip()
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        ccma.workspace(MODEL, RANGES, resolution=20, client=client)  # workers import ccma and load the model
        small_rows, small = measure(100, REPS, client, True)
        large_result = measure(316, 1, client, False) if large else None
    text = ["## Workspace sampling", "",
            f"`PYTHONPATH=build/python python3 benchmarks/workspace_bench.py{' --large' if large else ''}` "
            f"({date}; {machine()}, shared with other builds, so noisy): `ccma.workspace` on 4dof_reduced, "
            "x in [-0.4, 0.4] m by z in [0.3, 1.2] m (the legs reach z = 0.85 m), continuation in 1 cm steps. "
            "All runs of a map give identical maps (checked).", ""]
    text += table(100, small_rows, small, REPS)
    if large_result:
        text += table(316, large_result[0], large_result[1], 1)
    text.append("The map is computed in tiles; a tile waits only for its neighbours nearer home, so threads "
                "and workers stay busy (docs/workspace.md, \"How a map is computed\"). The Dask client sends "
                "one task per ready tile, at most four times the workers' threads in flight. On this 2-core "
                "machine the client, the scheduler and the other builds share the cores with the two workers.")
    text += ["", REACHABILITY]
    out = "\n".join(text) + "\n"
    print(out)
    (ROOT / "benchmarks" / "results").mkdir(parents=True, exist_ok=True)
    (ROOT / "benchmarks" / "results" / "workspace.md").write_text(out)


if __name__ == "__main__":
    main()
