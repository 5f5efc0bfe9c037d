"""Run one conform job per part of a manifest on a Dask cluster.

    python3 -m conform.batch MANIFEST.csv --out-dir DIR [--local-workers N | --scheduler tcp://HOST:8786]

MANIFEST.csv: a header row, then one row per part: `id`, `job` (compare, fit_cylinder, pose_error, saddle, weld_layers,
profile, tube_joint), then the
job's options as columns named like the Python keyword arguments (scan, reference, transform, tolerance, ...). An
empty cell leaves that option at its default. Relative input paths are relative to the manifest's folder; output
options (out, out_deviation, ...) relative to DIR.

Each part writes DIR/<id>.json (the CLI's --json for that part) and the outputs it names; a part that fails writes
DIR/<id>.error.txt instead and never stops the others. DIR/summary.csv gets one row per part: id, job, ok, the
headline figures and the error. A rerun skips the parts whose JSON exists (resume) and retries the failed ones.
"""

import argparse
import csv
import json
import os
import re
import sys

# Per job: the CLI's exit-0 test on its JSON, and the figures summary.csv shows.
HEADLINES = {
    "align": (lambda j: j["converged"], ["rms_mm", "inlier_fraction", "trust", "termination"]),
    "compare": (lambda j: j["matched"] > 0,
                ["points", "matched", "rms_mm", "p95_abs_mm", "in_tolerance_pct", "within_tolerance"]),
    "fit_cylinder": (lambda j: j["ok"], ["radius_mm", "rms_mm", "inlier_fraction", "termination"]),
    "pose_error": (lambda j: True, ["rotation_deg", "translation_mm"]),
    "saddle": (lambda j: j["converged"], ["points", "path_length_mm", "speed_ripple_pct"]),
    "profile": (lambda j: j["ok"], ["edge_points", "edge_rms_mm", "mapped_points", "termination"]),
    "tube_joint": (lambda j: j["ok"], ["points", "path_length_mm", "condition", "termination"]),
    "export": (lambda j: True, ["frames", "targets", "parts", "max_orientation_step_deg"]),
    "sicp": (lambda j: j["trusted"], ["rms_mm", "trajectory_rows", "termination"]),
    "weld_layers": (lambda j: j["ok"], ["layers", "paths", "total_length_mm", "damage_coverage_pct", "termination"]),
}
INPUTS = {"scan", "reference", "transform", "input", "transform_a", "transform_b", "eroded", "edge", "features", "second_edge",
          "leg", "stub", "leg_pose", "leg_markers", "stub_markers", "groove_table",
          "contour", "trajectory", "surface", "truth", "path", "frame"}
_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def _value(text):
    if re.fullmatch(r"[+-]?\d+", text):
        return int(text)
    if _NUMBER.match(text) or text.lower() in ("inf", "-inf"):
        return float(text)
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    return text


def part_options(row, manifest_dir, out_dir):
    """The keyword arguments of one manifest row (id and job removed)."""
    options = {}
    for key, text in row.items():
        if key in ("id", "job") or text is None or text.strip() == "":
            continue
        text = text.strip()
        if key in INPUTS:
            options[key] = os.path.join(manifest_dir, text)
        elif key == "out" or key.startswith("out_"):
            options[key] = os.path.join(out_dir, text)
        elif key in ("axis", "web_normal", "groove_deg", "wall_thickness", "preferred_x"):
            options[key] = [float(v) for v in re.split(r"[ ,]+", text)]
        else:
            options[key] = _value(text)
    return options


def _write_atomically(path, text):
    temporary = f"{path}.{os.getpid()}.tmp"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(temporary, path)


def run_part(row, manifest_dir, out_dir):
    """Run one part where it is called (a Dask worker, or here); returns its summary row. Never raises."""
    import conform  # on the worker

    part_id, job = row.get("id", ""), row.get("job", "")
    error_path = os.path.join(out_dir, f"{part_id}.error.txt")
    try:
        if job not in HEADLINES:
            raise conform.Error(f"unknown job {job!r}; one of {', '.join(sorted(HEADLINES))}")
        result = conform.JOBS[job](**part_options(row, manifest_dir, out_dir))
        values = result.to_dict()
        _write_atomically(os.path.join(out_dir, f"{part_id}.json"), json.dumps(values, indent=2) + "\n")
        if os.path.exists(error_path):
            os.remove(error_path)
        return summary_row(part_id, job, values, "")
    except Exception as e:  # a failing part never stops the others
        message = f"{type(e).__name__}: {e}" if not isinstance(e, conform.Error) else str(e)
        _write_atomically(error_path, message + "\n")
        return summary_row(part_id, job, None, message)


def summary_row(part_id, job, values, error):
    row = {"id": part_id, "job": job, "ok": False, "error": error}
    if values is not None:
        ok, figures = HEADLINES[job]
        row["ok"] = bool(ok(values))
        for key in figures:
            row[key] = values.get(key)
        if not row["ok"] and not error:
            row["error"] = values.get("termination") or "the job ran but did not succeed"
    return row


def read_manifest(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    ids = [r.get("id", "") for r in rows]
    bad = [i for i in ids if not re.fullmatch(r"[A-Za-z0-9._-]+", i or "")]
    if bad or len(set(ids)) != len(ids):
        raise ValueError(f"{path}: every row needs a unique id of letters, digits, '.', '_', '-' (bad: {bad[:3]})")
    return rows


def write_summary(path, rows):
    columns = ["id", "job", "ok"]
    for row in rows:
        columns += [k for k in row if k not in columns and k != "error"]
    columns.append("error")
    with open(f"{path}.tmp", "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if v is None else v) for k, v in row.items()})
    os.replace(f"{path}.tmp", path)


def run_batch(manifest, out_dir, client):
    """Every part of the manifest on the Dask client; returns the summary rows in manifest order."""
    rows = read_manifest(manifest)
    manifest_dir = os.path.dirname(os.path.abspath(manifest))
    out_dir = os.path.abspath(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    summary = {}
    todo = []
    for row in rows:
        done = os.path.join(out_dir, f"{row['id']}.json")
        if os.path.exists(done) and row.get("job") in HEADLINES:  # resume
            with open(done, encoding="utf-8") as f:
                summary[row["id"]] = summary_row(row["id"], row["job"], json.load(f), "")
        else:
            todo.append(row)
    from distributed import as_completed

    futures = {client.submit(run_part, row, manifest_dir, out_dir, pure=False, key=f"conform-{row['id']}-{os.getpid()}"): row
               for row in todo}
    for future in as_completed(futures):
        row = futures[future]
        try:
            summary[row["id"]] = future.result()
        except Exception as e:  # the worker died (a crash, out of memory)
            summary[row["id"]] = summary_row(row["id"], row.get("job", ""), None, f"{type(e).__name__}: {e}")
    ordered = [summary[row["id"]] for row in rows]
    write_summary(os.path.join(out_dir, "summary.csv"), ordered)
    return ordered


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m conform.batch", description=__doc__.split("\n\n")[0])
    parser.add_argument("manifest", help="CSV: id, job, then the job's options as columns")
    parser.add_argument("--out-dir", required=True, help="where <id>.json, outputs and summary.csv go")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--local-workers", type=int, default=None, help="processes of a LocalCluster (default: cores)")
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    args = parser.parse_args(argv)

    from distributed import Client, LocalCluster

    try:
        if args.scheduler:
            client = Client(args.scheduler)
            cluster = None
        else:
            # One OpenMP thread per worker process: the workers, not the threads of one job, share the cores.
            cluster = LocalCluster(n_workers=args.local_workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, env={"OMP_NUM_THREADS": "1"})
            client = Client(cluster)
    except OSError as e:
        print(f"conform.batch: error: cannot reach the scheduler: {e}", file=sys.stderr)
        return 2
    try:
        rows = run_batch(args.manifest, args.out_dir, client)
    except (OSError, ValueError) as e:
        print(f"conform.batch: error: {e}", file=sys.stderr)
        return 2
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    failed = [r for r in rows if not r["ok"]]
    print(f"{len(rows) - len(failed)} of {len(rows)} parts ok; summary in {os.path.join(args.out_dir, 'summary.csv')}",
          file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
