"""Run one conform job per part of a manifest on a Dask cluster.

    python3 -m conform.batch MANIFEST.csv --out-dir DIR [--local-workers N | --scheduler tcp://HOST:8786]
                             [--part-timeout SECONDS]

MANIFEST.csv: a header row, then one row per part: `id`, `job` (compare, inspect, fit_cylinder, pose_error, saddle,
weld_layers, profile, tube_joint), then the
job's options as columns named like the Python keyword arguments (scan, reference, transform, tolerance, ...). An
empty cell leaves that option at its default. Relative input paths are relative to the manifest's folder; output
options (out, out_deviation, ..., report) relative to DIR, and must stay in it.

Each part runs in its own process (a crash or a timeout is that part's failure) and writes DIR/<id>.json (the CLI's
--json for that part) and the outputs it names; a part that fails writes DIR/<id>.error.txt instead and never stops
the others. DIR/summary.csv gets one row per part: id, job, ok, the headline figures and the error. A rerun skips the
parts done with the same job, options and inputs (resume) and runs the others again. With `inspect` parts,
DIR/inspect_faces.csv gets one row per CAD face across those parts (statistical process control): the parts that
measured it, the mean, standard deviation (n - 1), min and max of its per-part mean deviation, its form's mean and
max, a cylinder's radius mean and standard deviation, and with tolerances Cp and Cpk of the mean deviation and Cpk of
the form (one-sided). DIR/inspect_features.csv gets one row per hole or boss (the JSON's `features`: the cylindrical
faces on one cylinder) across those parts: the same deviation figures, the diameter's mean, standard deviation, min
and max, the position's mean and max, and with size or position limits Cp and Cpk of the diameter and Cpk of the
position (one-sided).
"""

import argparse
import csv
import hashlib
import json
import os
import re
import signal
import stat
import subprocess
import sys
import tempfile

# Per job: the CLI's exit-0 test on its JSON, and the figures summary.csv shows.
HEADLINES = {
    "align": (lambda j: j["converged"], ["rms_mm", "inlier_fraction", "trust", "termination"]),
    "inspect": (lambda j: j["ok"], ["points", "assigned", "verdict", "termination"]),
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
INPUTS = {"scan", "reference", "transform", "tolerances", "input", "transform_a", "transform_b", "eroded", "edge", "features", "second_edge",
          "leg", "stub", "leg_pose", "leg_markers", "stub_markers", "groove_table",
          "contour", "trajectory", "surface", "truth", "path", "frame"}
DEFAULT_PART_TIMEOUT_S = 3600.0
FACES_CSV = "inspect_faces.csv"  # in DIR: the inspect parts' faces across parts
FEATURES_CSV = "inspect_features.csv"  # in DIR: the inspect parts' holes and bosses across parts
STATE_DIR = ".conform-batch"  # in DIR: the resume key of each part done (<id>.key)
_RESULT = "conform.batch result: "  # the line a part's process prints its summary row on
_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def _value(text):
    if re.fullmatch(r"[+-]?\d+", text):
        return int(text)
    if _NUMBER.match(text) or text.lower() in ("inf", "-inf"):
        return float(text)
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    return text


def is_output(key):
    return key in ("out", "report") or key.startswith("out_")


def output_path(text, out_dir, part_id, key):
    """DIR/text, or ValueError when it would be written outside DIR: an absolute path, a `..` component, or a path
    that leaves DIR through a symbolic link (DIR's own links resolved first)."""
    where = f"part {part_id}: {key}={text!r}"
    if os.path.isabs(text) or text.startswith("~"):
        raise ValueError(f"{where}: an absolute path; outputs are relative to --out-dir and stay in it")
    if ".." in re.split(r"[/\\]", text):
        raise ValueError(f"{where}: '..' leaves --out-dir; outputs stay in it")
    path = os.path.join(out_dir, text)
    real_dir = os.path.realpath(out_dir)
    real = os.path.realpath(path)
    if real == real_dir or os.path.commonpath([real, real_dir]) != real_dir:
        raise ValueError(f"{where}: resolves to {real} (through a symbolic link), outside --out-dir {real_dir}")
    return path


def part_options(row, manifest_dir, out_dir):
    """The keyword arguments of one manifest row (id and job removed). Raises ValueError for an output that would
    leave out_dir."""
    options = {}
    for key, text in row.items():
        if key in ("id", "job") or key is None or text is None or text.strip() == "":
            continue
        text = text.strip()
        if key in INPUTS:
            options[key] = os.path.join(manifest_dir, text)
        elif is_output(key):
            options[key] = output_path(text, out_dir, row.get("id", ""), key)
        elif key in ("axis", "web_normal", "groove_deg", "wall_thickness", "preferred_x"):
            options[key] = [float(v) for v in re.split(r"[ ,]+", text)]
        elif key == "datums":
            options[key] = [int(v) for v in re.split(r"[ ,]+", text)]
        else:
            options[key] = _value(text)
    return options


def _file_id(path):
    """What names one file: (device, inode) when it exists, else its absolute path with links resolved."""
    try:
        st = os.stat(path)
        return ("inode", st.st_dev, st.st_ino)
    except OSError:
        return ("path", os.path.realpath(path))


def check_outputs(parts, manifest, out_dir):
    """ValueError, before anything runs, when two parts (or one part twice) would write one file, when a part would
    write another part's input, the manifest or one of the batch's own files (summary.csv, <id>.json,
    <id>.error.txt, .conform-batch/): parts run at the same time, so the last one would silently win."""
    own = {_file_id(os.path.join(out_dir, "summary.csv")): "summary.csv",
           _file_id(os.path.join(out_dir, FACES_CSV)): FACES_CSV,
           _file_id(os.path.join(out_dir, STATE_DIR)): STATE_DIR,
           _file_id(manifest): "the manifest"}
    for part_id, _, _ in parts:
        own[_file_id(os.path.join(out_dir, f"{part_id}.json"))] = f"{part_id}.json"
        own[_file_id(os.path.join(out_dir, f"{part_id}.error.txt"))] = f"{part_id}.error.txt"
    state = os.path.realpath(os.path.join(out_dir, STATE_DIR))
    inputs = {}
    for part_id, _, options in parts:
        for key, value in options.items():
            if key in INPUTS:
                inputs.setdefault(_file_id(value), (part_id, key))
    written = {}
    for part_id, _, options in parts:
        for key, value in options.items():
            if not is_output(key):
                continue
            name = _file_id(value)
            where = f"part {part_id}: {key}={os.path.relpath(value, out_dir)!r}"
            if os.path.commonpath([os.path.realpath(value), state]) == state:
                raise ValueError(f"{where}: is in {STATE_DIR}, which the batch writes itself")
            if name in own:
                raise ValueError(f"{where}: is {own[name]}, which the batch writes itself")
            if name in written:
                other, other_key = written[name]
                raise ValueError(f"{where}: part {other} writes it too ({other_key}); each output needs its own file")
            if name in inputs and inputs[name][0] != part_id:
                raise ValueError(f"{where}: is an input of part {inputs[name][0]} ({inputs[name][1]}); parts run at "
                                 "the same time, write it to another file")
            written[name] = (part_id, key)


def part_key(job, options):
    """The resume key of a part: its job, its options and, for each input file, its path, size and modification
    time (nanoseconds). A part is done when its key is the one stored at its last success."""
    files = {}
    for key, value in sorted(options.items()):
        paths = [value] if key in INPUTS else []
        if key == "init" and isinstance(value, str) and value.startswith("pairs:"):
            paths = [value[len("pairs:"):]]
        for path in paths:
            try:
                st = os.stat(path)
                files[path] = [os.path.realpath(path), st.st_size, st.st_mtime_ns]
            except OSError as e:
                files[path] = [None, e.errno]
    text = json.dumps({"job": job, "options": options, "inputs": files}, sort_keys=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _regular(path):
    """Whether path is a regular file (not followed if a link), without opening it: a FIFO would block the open."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def _special(path):
    try:
        mode = os.lstat(path).st_mode
    except OSError:
        return False
    return not stat.S_ISREG(mode)


def _read_small(path):
    """The text of a regular file, or None (absent, special or unreadable). Never opens a FIFO or a device."""
    if not _regular(path):
        return None
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0))
    except OSError:
        return None
    with os.fdopen(fd, encoding="utf-8") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):  # replaced between the lstat and the open
            return None
        return f.read()


def _write_atomically(path, text):
    """A new temporary (never an existing name: a FIFO there would block) renamed over path."""
    fd, temporary = tempfile.mkstemp(prefix=os.path.basename(path) + ".", suffix=".tmp", dir=os.path.dirname(path))
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(temporary, path)
    except BaseException:
        if os.path.lexists(temporary):
            os.unlink(temporary)
        raise


def _remove(path):
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass


def _record(out_dir, part_id, values, error, key):
    """The files of a part's outcome: its JSON and resume key, or its error file (the stale JSON and key removed)."""
    json_path = os.path.join(out_dir, f"{part_id}.json")
    key_path = os.path.join(out_dir, STATE_DIR, f"{part_id}.key")
    error_path = os.path.join(out_dir, f"{part_id}.error.txt")
    if error:
        _remove(key_path)
        _remove(json_path)
        _write_atomically(error_path, error + "\n")
    else:
        _remove(key_path)
        _write_atomically(json_path, json.dumps(values, indent=2) + "\n")
        os.makedirs(os.path.dirname(key_path), exist_ok=True)
        _write_atomically(key_path, key + "\n")
        _remove(error_path)


def run_part(spec):
    """Run one part in this process and record its outcome; returns its summary row. Never raises."""
    import conform

    part_id, job, out_dir = spec["id"], spec["job"], spec["out_dir"]
    try:
        if job not in HEADLINES:
            raise conform.Error(f"unknown job {job!r}; one of {', '.join(sorted(HEADLINES))}")
        values = conform.JOBS[job](**spec["options"]).to_dict()
        error = ""
    except Exception as e:  # a failing part never stops the others
        values, error = None, (str(e) if isinstance(e, conform.Error) else f"{type(e).__name__}: {e}")
    _record(out_dir, part_id, values, error, spec["key"])
    return summary_row(part_id, job, values, error)


def _child_environment():
    """The environment of a part's process: this package first on its path, one OpenMP thread unless set."""
    env = dict(os.environ)
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env["PYTHONPATH"] = os.pathsep.join([here] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    env.setdefault("OMP_NUM_THREADS", "1")
    return env


def run_part_isolated(spec, timeout_s, command=None):
    """Run one part in a process of its own (`python3 -m conform.batch --run-one`, the spec on stdin), so that a crash
    in native code or a timeout fails this part only; returns its summary row. Never raises. `command` replaces the
    child's command line (tests)."""
    command = command or [sys.executable, "-m", "conform.batch", "--run-one"]
    part_id, job, out_dir = spec["id"], spec["job"], spec["out_dir"]
    try:
        done = subprocess.run(command, input=json.dumps(spec), capture_output=True, text=True,
                              timeout=timeout_s if timeout_s and timeout_s > 0 else None, env=_child_environment())
        for line in reversed(done.stdout.splitlines()):
            if line.startswith(_RESULT) and done.returncode == 0:
                return json.loads(line[len(_RESULT):])
        if done.returncode < 0:
            try:
                name = signal.Signals(-done.returncode).name
            except ValueError:
                name = f"signal {-done.returncode}"
            error = f"the part's process was killed by {name} (a crash)"
        else:
            error = f"the part's process exited with code {done.returncode} without a result"
        tail = done.stderr.strip().splitlines()[-5:]
        if tail:
            error += "; its last messages: " + " | ".join(tail)
    except subprocess.TimeoutExpired:
        error = f"timed out after {timeout_s:g} s (--part-timeout); the part's process was killed"
    except OSError as e:
        error = f"cannot start the part's process: {e}"
    try:
        _record(out_dir, part_id, None, error, spec["key"])
    except OSError as e:
        error += f" (and its error file cannot be written: {e})"
    return summary_row(part_id, job, None, error)


def summary_row(part_id, job, values, error):
    row = {"id": part_id, "job": job, "ok": False, "error": error}
    if values is not None and job in HEADLINES:
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
    bad = [i for i in ids if not re.fullmatch(r"[A-Za-z0-9._-]+", i or "") or i in (".", "..")]
    if bad or len(set(ids)) != len(ids):
        raise ValueError(f"{path}: every row needs a unique id of letters, digits, '.', '_', '-' (bad: {bad[:3]})")
    return rows


def write_summary(path, rows):
    columns = ["id", "job", "ok"]
    for row in rows:
        columns += [k for k in row if k not in columns and k != "error"]
    columns.append("error")
    fd, temporary = tempfile.mkstemp(prefix="summary.csv.", suffix=".tmp", dir=os.path.dirname(path))
    with os.fdopen(fd, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if v is None else v) for k, v in row.items()})
    os.replace(temporary, path)


def _resumed(out_dir, part_id, job, key):
    """The summary row of a part done with this key, or None (then it runs). Special files are never opened."""
    json_path = os.path.join(out_dir, f"{part_id}.json")
    key_path = os.path.join(out_dir, STATE_DIR, f"{part_id}.key")
    for path in (json_path, key_path):
        if _special(path):
            print(f"conform.batch: {path} is not a regular file; ignored, part {part_id} runs again", file=sys.stderr)
            return None
    stored = _read_small(key_path)
    if stored is None or stored.strip() != key or job not in HEADLINES:
        return None
    text = _read_small(json_path)
    try:
        values = json.loads(text) if text is not None else None
    except ValueError:
        values = None
    return summary_row(part_id, job, values, "") if isinstance(values, dict) else None


def manifest_parts(manifest, out_dir):
    """(id, job, keyword arguments) of every part; ValueError when the manifest cannot be used (check_outputs)."""
    rows = read_manifest(manifest)
    manifest_dir = os.path.dirname(os.path.abspath(manifest))
    out_dir = os.path.abspath(out_dir)
    parts = [(row["id"], row.get("job", ""), part_options(row, manifest_dir, out_dir)) for row in rows]
    check_outputs(parts, manifest, out_dir)
    return parts


def run_batch(manifest, out_dir, client, part_timeout=DEFAULT_PART_TIMEOUT_S, part_command=None):
    """Every part of the manifest, each in a process of its own, on the Dask client (None: one after the other
    here); returns the summary rows in manifest order. Raises ValueError, before running anything, for a manifest
    whose outputs leave out_dir or collide. `part_command` replaces the part's command line (tests only)."""
    out_dir = os.path.abspath(out_dir)
    parts = manifest_parts(manifest, out_dir)
    os.makedirs(out_dir, exist_ok=True)
    summary = {}
    todo = []
    for part_id, job, options in parts:
        key = part_key(job, options)
        row = _resumed(out_dir, part_id, job, key)
        if row is not None:
            summary[part_id] = row
        else:
            todo.append({"id": part_id, "job": job, "options": options, "out_dir": out_dir, "key": key})
    if client is None:
        for spec in todo:
            summary[spec["id"]] = run_part_isolated(spec, part_timeout, part_command)
    else:
        from distributed import as_completed

        futures = {client.submit(run_part_isolated, spec, part_timeout, part_command, pure=False,
                                 key=f"conform-{spec['id']}-{os.getpid()}"): spec for spec in todo}
        for future in as_completed(futures):
            spec = futures[future]
            try:
                summary[spec["id"]] = future.result()
            except Exception as e:  # the worker itself died (out of memory, killed)
                summary[spec["id"]] = summary_row(spec["id"], spec["job"], None, f"{type(e).__name__}: {e}")
    ordered = [summary[part_id] for part_id, _, _ in parts]
    write_summary(os.path.join(out_dir, "summary.csv"), ordered)
    inspected = [row for row in ordered if row["job"] == "inspect" and row["ok"]]
    faces = inspect_face_statistics(inspected, out_dir)
    if faces:
        write_summary(os.path.join(out_dir, FACES_CSV), faces)
    features = inspect_feature_statistics(inspected, out_dir)
    if features:
        write_summary(os.path.join(out_dir, FEATURES_CSV), features)
    return ordered


def _capability(values, lower, upper):
    """Cp and Cpk of `values` (mean and n - 1 standard deviation) against [lower, upper] (either may be None:
    one-sided, no Cp); (None, None) for fewer than 2 values or no spread."""
    if len(values) < 2:
        return None, None
    mean = sum(values) / len(values)
    sigma = (sum((v - mean) ** 2 for v in values) / (len(values) - 1)) ** 0.5
    if sigma == 0.0 or (lower is None and upper is None):
        return None, None
    cp = (upper - lower) / (6.0 * sigma) if lower is not None and upper is not None else None
    sides = [(upper - mean) if upper is not None else None, (mean - lower) if lower is not None else None]
    cpk = min(s for s in sides if s is not None) / (3.0 * sigma)
    return cp, cpk


def _inspected(rows, out_dir, key):
    """Per id, the objects of the JSON array `key` ("faces", "features") over the inspect parts of `rows` (read from
    their DIR/<id>.json), in part order. Matched by id: the parts are inspected against the same CAD."""
    per_id = {}
    for row in rows:
        text = _read_small(os.path.join(out_dir, f"{row['id']}.json"))
        if text is None:
            continue
        for item in json.loads(text).get(key, []):
            per_id.setdefault(item["id"], []).append(item)
    return per_id


def _mean(values):
    return sum(values) / len(values) if values else None


def _std(values):
    """The n - 1 standard deviation; None for fewer than two values."""
    if len(values) < 2:
        return None
    mean = _mean(values)
    return (sum((x - mean) ** 2 for x in values) / (len(values) - 1)) ** 0.5


def _deviation_figures(measured):
    """The deviation figures faces and features share: over the parts that measured it, the mean and standard
    deviation of the per-part mean deviation, the min and max deviation, the form's mean and max."""
    means = [f["mean_mm"] for f in measured]
    forms = [f["form_mm"] for f in measured if f.get("form_mm") is not None]
    return {"parts": len(measured), "mean_mm": _mean(means), "std_mm": _std(means),
            "min_mm": min((f["min_mm"] for f in measured), default=None),
            "max_mm": max((f["max_mm"] for f in measured), default=None), "form_mean_mm": _mean(forms),
            "form_max_mm": max(forms, default=None)}


def _measured(items):
    return [f for f in items if f.get("points", 0) > 0 and f.get("mean_mm") is not None]


def inspect_face_statistics(rows, out_dir):
    """One row per CAD face over the inspect parts of `rows`: the module docstring's figures."""
    per_face = _inspected(rows, out_dir, "faces")
    out = []
    for face_id in sorted(per_face):
        faces = per_face[face_id]
        measured = _measured(faces)
        means = [f["mean_mm"] for f in measured]
        forms = [f["form_mm"] for f in measured if f.get("form_mm") is not None]
        radii = [f["radius_mm"] for f in measured if f.get("radius_mm") is not None]
        tolerance = next((f["tolerance"] for f in faces if f.get("tolerance")), None) or {}
        lower, upper, form_limit = tolerance.get("lower_mm"), tolerance.get("upper_mm"), tolerance.get("form_mm")
        cp, cpk = _capability(means, lower, upper)
        _, form_cpk = _capability(forms, None, form_limit) if form_limit is not None else (None, None)
        out.append({"id": face_id, "job": "inspect", "ok": bool(measured), "type": faces[0]["type"],
                    **_deviation_figures(measured),
                    "radius_mean_mm": _mean(radii), "radius_std_mm": _std(radii),
                    "lower_mm": lower, "upper_mm": upper, "form_limit_mm": form_limit, "cp": cp, "cpk": cpk,
                    "form_cpk": form_cpk, "error": "" if measured else "no part measured it"})
    return out


def inspect_feature_statistics(rows, out_dir):
    """One row per hole or boss over the inspect parts of `rows`: the module docstring's figures. A feature's size
    and position are those of its fitted cylinder; a part whose fit failed counts for its deviation, not its size."""
    per_feature = _inspected(rows, out_dir, "features")
    out = []
    for feature_id in sorted(per_feature):
        features = per_feature[feature_id]
        measured = _measured(features)
        fitted = [f for f in measured if f.get("diameter_mm") is not None]
        diameters = [f["diameter_mm"] for f in fitted]
        positions = [f["position_mm"] for f in fitted if f.get("position_mm") is not None]
        tolerance = next((f["tolerance"] for f in features if f.get("tolerance")), None) or {}
        lower, upper = tolerance.get("diameter_lower_mm"), tolerance.get("diameter_upper_mm")
        position_limit = tolerance.get("position_mm")
        cp, cpk = _capability(diameters, lower, upper)
        _, position_cpk = _capability(positions, None, position_limit) if position_limit is not None else (None, None)
        first = features[0]
        out.append({"id": feature_id, "job": "inspect", "ok": bool(fitted), "kind": first.get("kind"),
                    "faces": "+".join(str(f) for f in first.get("faces", [])), **_deviation_figures(measured),
                    "fitted_parts": len(fitted), "nominal_diameter_mm": first.get("nominal_diameter_mm"),
                    "diameter_mean_mm": _mean(diameters), "diameter_std_mm": _std(diameters),
                    "diameter_min_mm": min(diameters, default=None), "diameter_max_mm": max(diameters, default=None),
                    "position_mean_mm": _mean(positions), "position_max_mm": max(positions, default=None),
                    "diameter_lower_mm": lower, "diameter_upper_mm": upper, "position_limit_mm": position_limit,
                    "cp": cp, "cpk": cpk, "position_cpk": position_cpk,
                    "error": "" if fitted else ("no part fitted it" if measured else "no part measured it")})
    return out


def run_one():
    """`--run-one`: the part's spec (JSON) on stdin, its summary row on stdout after _RESULT."""
    spec = json.load(sys.stdin)
    row = run_part(spec)
    sys.stdout.write(_RESULT + json.dumps(row) + "\n")
    sys.stdout.flush()
    return 0


def _timeout(text):
    value = float(text)
    if not value >= 0:
        raise argparse.ArgumentTypeError("give seconds >= 0 (0: no limit)")
    return value


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv == ["--run-one"]:
        return run_one()
    parser = argparse.ArgumentParser(prog="python3 -m conform.batch", description=__doc__.split("\n\n")[0])
    parser.add_argument("manifest", help="CSV: id, job, then the job's options as columns")
    parser.add_argument("--out-dir", required=True,
                        help="where <id>.json, <id>.error.txt, summary.csv and the parts' outputs go (outputs may "
                             "not leave it: no absolute paths, no '..', no links out)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--local-workers", type=int, default=None, help="processes of a LocalCluster (default: cores)")
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    parser.add_argument("--part-timeout", type=_timeout, default=DEFAULT_PART_TIMEOUT_S, metavar="SECONDS",
                        help="a part still running after this many seconds is killed and fails "
                             f"(default: {DEFAULT_PART_TIMEOUT_S:g} s; 0: no limit)")
    args = parser.parse_args(argv)
    try:
        manifest_parts(args.manifest, args.out_dir)  # before a cluster is started
    except (OSError, ValueError) as e:
        print(f"conform.batch: error: {e}", file=sys.stderr)
        return 2

    from distributed import Client, LocalCluster

    try:
        if args.scheduler:
            client = Client(args.scheduler)
            cluster = None
        else:
            # One OpenMP thread per part: the workers, not the threads of one job, share the cores.
            cluster = LocalCluster(n_workers=args.local_workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, env={"OMP_NUM_THREADS": "1"})
            client = Client(cluster)
    except OSError as e:
        print(f"conform.batch: error: cannot reach the scheduler: {e}", file=sys.stderr)
        return 2
    from conform import batch  # not __main__'s copy: the workers import the module, the functions go by name

    try:
        rows = batch.run_batch(args.manifest, args.out_dir, client, part_timeout=args.part_timeout)
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
