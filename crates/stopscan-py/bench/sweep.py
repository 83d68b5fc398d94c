"""A sweep on Ray with WORKERS workers against the same sweep run serially, in one run on one
machine.

Usage: python bench/sweep.py [DIR] [--workers 2] [--strategy all] [--bin STOPSCAN_BINARY]
Without DIR, the inputs are generated here with the CLI (seeded, so every run sweeps the
same files): 16 office floors of 4 to 7 rooms per side and 16 forests of 6 to 12 pillars,
every strategy on each (192 runs). The local Ray cluster is started before the clock starts
(its start-up is reported apart), and the serial sweep runs in this process, one run after
the other. Both tables must be equal. Prints one JSON object.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings

import stopscan


def generate(folder, binary):
    for k in range(16):
        subprocess.run([binary, "generate", "office", "--size", str(4 + k % 4), "--seed", str(k),
                        "--output", os.path.join(folder, f"office{k:02}.geojson")],
                       check=True, capture_output=True)
        subprocess.run([binary, "--seed", str(k), "generate", "forest", "--size", str(6 + k % 7),
                        "--output", os.path.join(folder, f"forest{k:02}.geojson")],
                       check=True, capture_output=True)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir", nargs="?")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--strategy", default="all")
    p.add_argument("--bin", default="target/release/stopscan")
    # The lower bounds get a budget of steps, not the CLI's 5 s: a deadline cuts them where
    # the machine's load puts it, and two runs per core compete on Ray, not serially.
    p.add_argument("--bounds-steps", type=int, default=5000)
    a = p.parse_args()
    import ray

    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as tmp:
        folder = a.dir
        if folder is None:
            folder = tmp
            generate(folder, a.bin)
        t = time.perf_counter()
        ray.init(num_cpus=a.workers, include_dashboard=False, log_to_driver=False)
        init = time.perf_counter() - t
        # One task first, so that the workers have imported stopscan before the clock starts.
        stopscan.sweep(stopscan._sweep._files(folder)[:1], "depth_first", backend="ray")
        t = time.perf_counter()
        serial = stopscan.sweep(folder, a.strategy, backend="serial",
                                bounds_steps=a.bounds_steps)
        serial_s = time.perf_counter() - t
        t = time.perf_counter()
        on_ray = stopscan.sweep(folder, a.strategy, backend="ray",
                                bounds_steps=a.bounds_steps)
        ray_s = time.perf_counter() - t
        ray.shutdown()
    assert on_ray == serial, "the Ray sweep's table differs from the serial one"
    print(json.dumps({
        "runs": len(serial),
        "workers": a.workers,
        "cores": os.cpu_count(),
        "serial_s": round(serial_s, 3),
        "ray_s": round(ray_s, 3),
        "speedup": round(serial_s / ray_s, 3),
        "ray_start_s": round(init, 3),
        "bounds_steps": a.bounds_steps,
        "equal": True,
    }, indent=2))


if __name__ == "__main__":
    sys.exit(main())
