"""Peak memory of the client of a distributed workspace map (issue 28): the
client's maximum resident set size while ccma.workspace runs a 99,856-sample
map on a 2-worker Dask LocalCluster, with and without a store, against the map
itself (the arrays returned). Prints a Markdown table; its section of
benchmarks/RESULTS.md is benchmarks/results/workspace_memory.md (scripts/results.sh).

    PYTHONPATH=build/python python3 benchmarks/workspace_memory.py
"""
import pathlib
import platform
import resource
import sys
import tempfile
import time

import ccma

ROOT = pathlib.Path(__file__).resolve().parents[1]
MODEL = str(ROOT / "models" / "4dof_reduced.yaml")
MAP = dict(ranges={"x": (-0.4, 0.4), "z": (0.3, 1.2)}, resolution=316)


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def map_mib(m):
    return sum(getattr(v, "nbytes", 0) for v in m.values()) / 2 ** 20


def main():
    from distributed import Client, LocalCluster
    rows = []
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        before = peak_mib()
        start = time.perf_counter()
        m = ccma.workspace(MODEL, client=client, **MAP)
        rows.append(("no store", time.perf_counter() - start, before, peak_mib(), map_mib(m), len(m["reachable"])))
        del m
        with tempfile.TemporaryDirectory() as d:
            before = peak_mib()
            start = time.perf_counter()
            m = ccma.workspace(MODEL, client=client, store=d + "/map.zarr", **MAP)
            rows.append(("store=", time.perf_counter() - start, before, peak_mib(), map_mib(m), len(m["reachable"])))
    print(f"Client peak resident memory, {rows[0][5]:,} samples, 2-worker LocalCluster "
          f"({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; {platform.machine()}, Linux):\n")
    print("| run | seconds | client peak RSS before [MiB] | after [MiB] | the map's arrays [MiB] |")
    print("|---|---|---|---|---|")
    for name, seconds, before, after, size, _ in rows:
        print(f"| {name} | {seconds:.1f} | {before:.0f} | {after:.0f} | {size:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
