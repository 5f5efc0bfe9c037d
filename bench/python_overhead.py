"""Per-part cost of the Python binding against the CLI on the same inputs (docs/python.md, "Figures").

    PYTHONPATH=build/python python3 bench/python_overhead.py build/conform SCAN REFERENCE [repeats]

Prints the median wall time of `conform compare --json` (a process per part, JSON parsed) and of conform.compare
(in process), and of `conform pose-error` against conform.pose_error (a tiny job: the fixed cost of each route).
"""

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import conform


def median_seconds(run, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    exe, scan, reference = sys.argv[1:4]
    repeats = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    with tempfile.TemporaryDirectory() as d:
        identity = os.path.join(d, "I.txt")
        with open(identity, "w") as f:
            f.write("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n")
        cases = {
            "compare": (lambda: json.loads(subprocess.run([exe, "compare", "--scan", scan, "--reference", reference,
                                                           "--json"], capture_output=True, check=True).stdout),
                        lambda: conform.compare(scan, reference).to_dict()),
            "pose_error": (lambda: json.loads(subprocess.run([exe, "pose-error", "--transform", identity,
                                                              "--transform", identity, "--json"],
                                                             capture_output=True, check=True).stdout),
                           lambda: conform.pose_error(identity, identity).to_dict()),
        }
        for name, (cli, python) in cases.items():
            assert cli() == python(), name
            t_cli, t_py = median_seconds(cli, repeats), median_seconds(python, repeats)
            print(f"{name:11s} CLI {1000 * t_cli:8.1f} ms   Python {1000 * t_py:8.1f} ms   "
                  f"CLI - Python {1000 * (t_cli - t_py):7.1f} ms   ratio {t_cli / t_py:5.2f}")


if __name__ == "__main__":
    main()
