"""Python's visibility against the CLI's, side by side in one run on one machine.

Usage: python bench/visibility.py ENV_FILE [STOPSCAN_BINARY]
Both answer the file's own QUERIES (up to 1,000): the CLI's `bench visibility` (median of
15 passes, the triangulation built beforehand, one thread, regions not kept) and
`stopscan.visibility` on the same points (median of 15 calls, after one call that builds and
keeps the triangulation), which returns every region to Python: on one thread
(`threads=1`) and on every core (the default). The two alternate ROUNDS times (default 5), and each side's best
median is compared: on a shared 2-core machine a single pass of either varies by ±30%.
Prints one JSON object.
"""

import json
import statistics
import subprocess
import sys
import time

import numpy as np

import stopscan


def queries(path):
    lines = open(path).read().split("\n")
    start = next(k for k, line in enumerate(lines) if line.strip().upper().startswith("QUERIES"))
    out = []
    for line in lines[start + 1:]:
        f = line.split()
        if len(f) >= 2:
            try:
                out.append((float(f[0]), float(f[1])))
            except ValueError:
                break
    return np.array(out[:1000])


def main(path, binary="target/release/stopscan", rounds=5):
    env = stopscan.load(path)
    pts = queries(path)
    stopscan.visibility(env, pts[:1])
    python, parallel, cli = [], [], []
    for _ in range(int(rounds)):
        for threads, into in ((1, python), (None, parallel)):
            runs = []
            for _ in range(15):
                t = time.perf_counter()
                regions = stopscan.visibility(env, pts, threads=threads)
                runs.append(time.perf_counter() - t)
                del regions
            into.append(statistics.median(runs) / len(pts) * 1e6)
        out = subprocess.run([binary, "bench", "visibility", "--env", path, "--repeat", "15"],
                             capture_output=True, text=True, check=True).stdout
        cli.append(1e6 / json.loads(out.strip().splitlines()[-1])["queries_per_second"])
    r = lambda xs: [round(x, 3) for x in xs]
    print(json.dumps({"env": path, "queries": len(pts),
                      "python_one_thread_per_query_us": r(python),
                      "python_all_cores_per_query_us": r(parallel),
                      "cli_per_query_us": r(cli),
                      "ratio_of_best_one_thread": round(min(python) / min(cli), 3),
                      "ratio_of_best_all_cores": round(min(parallel) / min(cli), 3)}))


if __name__ == "__main__":
    main(*sys.argv[1:])
