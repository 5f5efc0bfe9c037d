#!/usr/bin/env python3
"""Run `conform align` on real scan pairs with known poses and say, per pair, whether the pose is right and whether
conform accepted it.

Usage:
    scripts/eval_real_pairs.py CONFORM PAIRS_DIR [--truth-start] [--only NAME,...] [--units U] [--timeout S]
                               [--init I] [-- EXTRA_ALIGN_FLAGS ...]

PAIRS_DIR holds one folder per pair (docs/measurements/real_pairs.md says where the data comes from), each with
    source.* and target.*   the scan (conform's --scan) and its reference (--reference): any format conform reads
                            (.ply .pcd .xyz .txt .csv .stl .obj ...)
    T_target_source.txt     the truth: 4x4 row-major, p_target = T * p_source, in the files' units
    units                   optional, one word: the files' units (m, mm, cm, in); default m (--units overrides)
Each pair runs
    CONFORM align --scan SOURCE --reference TARGET --units U --init fpfh --json --out-transform TMP [EXTRA...]
Flags the script does not know are passed through to `conform align` as well (with or without `--`), e.g.
`--overlap 0.5 --free-tolerance-mm 1 --free-tolerance-deg 0.5`.

Definitions (the table's columns):
    rot deg, trans mm  the error of conform's T_ref_scan against the truth: the angle of R_found^T R_true, and
                       |t_found - t_true| (the translations of the 4x4 matrices, in mm; the files' origin is the
                       sensor's or the object's, within a few metres of the data).
    right              rot < 2 deg and trans < max(5 x the source's median point spacing, 1 % of the source's
                       bounding-box diagonal). The spacing is the median distance from 2000 sampled source points to
                       their nearest other source point.
    trust              the JSON's "trust": yes / check / no.
    exit               conform's exit code (0: accepted, the pose is "yes" or "check"; 1: refused; 2: bad input).
    s                  wall-clock seconds of the run.
For every refused, wrong or 'check' pair the verdict's reasons follow the table. The last line counts: right; right
and accepted (exit 0); wrong and accepted (exit 0 with a wrong pose: the worst case, a user would use it); accepted;
right but refused.

--truth-start: the source is first moved by the truth (a transformed copy, binary PLY of its points, in a temporary
folder), so the truth becomes the identity, and conform runs with --init none: does a right start stay right? The
table then gives how far the pose moved from the start (deg, mm) and "kept" (the same bound as "right").

Standard library only; reads PLY (ascii, binary), PCD (ascii, binary), and xyz/txt/csv/asc text for the statistics
and for the truth-start copy.
"""
import argparse
import json
import math
import os
import random
import struct
import subprocess
import sys
import tempfile
import time

MM_PER_UNIT = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}
CLOUD_EXTENSIONS = (".ply", ".pcd", ".xyz", ".txt", ".csv", ".asc", ".stl", ".obj")


# ---------------------------------------------------------------- reading points (statistics, truth-start copy)
def _ply_points(data):
    end = data.index(b"end_header")
    nl = data.index(b"\n", end)
    header = data[:end].decode("ascii", "replace").splitlines()
    body = data[nl + 1:]
    fmt = None
    elements = []  # (name, count, [(type, name) or ('list', count_type, item_type, name)])
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property" and elements:
            if w[1] == "list":
                elements[-1][2].append(("list", w[2], w[3], w[4]))
            else:
                elements[-1][2].append((w[1], w[2]))
    vertex = [e for e in elements if e[0] == "vertex"]
    if not vertex:
        return []
    if elements[0][0] != "vertex":
        raise ValueError("PLY with an element before 'vertex' is not supported here")
    _, n, props = vertex[0]
    names = [p[-1] for p in props]
    ix, iy, iz = names.index("x"), names.index("y"), names.index("z")
    if fmt == "ascii":
        rows = body.decode("ascii", "replace").split("\n")
        out = []
        for row in rows[:n]:
            v = row.split()
            out.append((float(v[ix]), float(v[iy]), float(v[iz])))
        return out
    codes = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h", "ushort": "H",
             "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I", "float": "f", "float32": "f",
             "double": "d", "float64": "d"}
    if any(p[0] == "list" for p in props):
        raise ValueError("PLY vertex lists are not supported here")
    order = "<" if fmt == "binary_little_endian" else ">"
    rec = order + "".join(codes[p[0]] for p in props)
    size = struct.calcsize(rec)
    return [(v[ix], v[iy], v[iz]) for v in struct.iter_unpack(rec, body[:n * size])]


def _pcd_points(data):
    header = {}
    pos = 0
    while True:
        nl = data.index(b"\n", pos)
        line = data[pos:nl].decode("ascii", "replace").strip()
        pos = nl + 1
        if not line or line.startswith("#"):
            continue
        w = line.split()
        header[w[0].upper()] = w[1:]
        if w[0].upper() == "DATA":
            break
    fields = header["FIELDS"]
    n = int(header["POINTS"][0])
    kind = header["DATA"][0]
    ix, iy, iz = fields.index("x"), fields.index("y"), fields.index("z")
    if kind == "ascii":
        out = []
        for row in data[pos:].decode("ascii", "replace").split("\n")[:n]:
            v = row.split()
            if len(v) >= len(fields):
                out.append((float(v[ix]), float(v[iy]), float(v[iz])))
        return out
    if kind != "binary":
        raise ValueError("PCD DATA %s is not supported here" % kind)
    sizes = [int(s) for s in header["SIZE"]]
    types = header["TYPE"]
    counts = [int(c) for c in header.get("COUNT", ["1"] * len(fields))]
    code = {("F", 4): "f", ("F", 8): "d", ("I", 1): "b", ("U", 1): "B", ("I", 2): "h", ("U", 2): "H",
            ("I", 4): "i", ("U", 4): "I", ("I", 8): "q", ("U", 8): "Q"}
    rec = "<" + "".join(code[(t, s)] * c for t, s, c in zip(types, sizes, counts))
    first = [sum(counts[:k]) for k in range(len(fields))]
    size = struct.calcsize(rec)
    return [(v[first[ix]], v[first[iy]], v[first[iz]]) for v in struct.iter_unpack(rec, data[pos:pos + n * size])]


def _text_points(data):
    out = []
    for line in data.decode("ascii", "replace").splitlines():
        w = line.replace(",", " ").replace(";", " ").split()
        if len(w) < 3 or line.lstrip().startswith("#"):
            continue
        try:
            out.append((float(w[0]), float(w[1]), float(w[2])))
        except ValueError:
            continue
    return out


def _obj_points(data):
    out = []
    for line in data.decode("ascii", "replace").splitlines():
        if line.startswith("v "):
            w = line.split()
            out.append((float(w[1]), float(w[2]), float(w[3])))
    return out


def _stl_points(data):
    if data[:5] == b"solid" and b"facet" in data[:1000]:
        return [tuple(float(x) for x in line.split()[1:4]) for line in data.decode("ascii", "replace").splitlines()
                if line.strip().startswith("vertex")]
    n = struct.unpack("<I", data[80:84])[0]
    out = []
    for k in range(n):
        v = struct.unpack("<12f", data[84 + 50 * k:84 + 50 * k + 48])
        out.extend([v[3:6], v[6:9], v[9:12]])
    return out


def read_points(path):
    """xyz of every point (mesh vertices for meshes), finite ones only."""
    with open(path, "rb") as f:
        data = f.read()
    ext = os.path.splitext(path)[1].lower()
    if ext == ".ply":
        pts = _ply_points(data)
    elif ext == ".pcd":
        pts = _pcd_points(data)
    elif ext == ".obj":
        pts = _obj_points(data)
    elif ext == ".stl":
        pts = _stl_points(data)
    else:
        pts = _text_points(data)
    return [p for p in pts if all(math.isfinite(c) for c in p)]


def write_ply(path, pts):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nend_header\n" % len(pts)).encode())
        f.write(b"".join(struct.pack("<fff", *p) for p in pts))


# ---------------------------------------------------------------- geometry
def median_spacing(pts, samples=2000):
    """Median distance from sampled points to their nearest other (distinct) point, by a grid search."""
    distinct = list(set(pts))
    if len(distinct) < 2:
        return 0.0
    lo = [min(p[i] for p in distinct) for i in range(3)]
    hi = [max(p[i] for p in distinct) for i in range(3)]
    diag = math.dist(lo, hi)
    cell = diag / max(20.0, len(distinct) ** (1.0 / 2.0))
    sample = random.Random(1).sample(distinct, min(samples, len(distinct)))
    for _ in range(30):
        grid = {}
        for p in distinct:
            grid.setdefault((math.floor(p[0] / cell), math.floor(p[1] / cell), math.floor(p[2] / cell)), []).append(p)
        found = []
        for p in sample:
            k = (math.floor(p[0] / cell), math.floor(p[1] / cell), math.floor(p[2] / cell))
            best = math.inf
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for dz in (-1, 0, 1):
                        for q in grid.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                            if q != p:
                                d = math.dist(p, q)
                                if d < best:
                                    best = d
            found.append(best)
        found.sort()
        median = found[len(found) // 2]
        if median <= cell:  # every neighbour within one cell was searched
            return median
        cell *= 2.0
    return median


def diagonal(pts):
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    return math.dist(lo, hi)


def read_matrix(path):
    rows = []
    with open(path) as f:
        for line in f:
            w = line.replace(",", " ").split()
            if len(w) == 4 and not line.lstrip().startswith("#"):
                rows.append([float(x) for x in w])
    if len(rows) != 4:
        raise ValueError("%s: expected 4 rows of 4 numbers" % path)
    return rows


def apply(T, p):
    return tuple(T[i][0] * p[0] + T[i][1] * p[1] + T[i][2] * p[2] + T[i][3] for i in range(3))


def pose_error(found, truth):
    """(rotation error deg, translation error) of found against truth, translation in the matrices' units."""
    trace = sum(found[k][i] * truth[k][i] for i in range(3) for k in range(3))  # trace(R_found^T R_truth)
    angle = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0))))
    return angle, math.dist([found[i][3] for i in range(3)], [truth[i][3] for i in range(3)])


def scaled(T, s):
    return [[T[i][0], T[i][1], T[i][2], T[i][3] * s] if i < 3 else list(T[i]) for i in range(4)]


# ---------------------------------------------------------------- pairs
def find_file(folder, stem):
    for ext in CLOUD_EXTENSIONS:
        p = os.path.join(folder, stem + ext)
        if os.path.isfile(p):
            return p
    return None


def list_pairs(root, only):
    pairs = []
    for name in sorted(os.listdir(root)):
        d = os.path.join(root, name)
        if not os.path.isdir(d) or name.startswith(("_", ".")):
            continue
        if only and name not in only:
            continue
        src, tgt = find_file(d, "source"), find_file(d, "target")
        truth = os.path.join(d, "T_target_source.txt")
        if src and tgt and os.path.isfile(truth):
            pairs.append((name, d, src, tgt, truth))
        else:
            print("skipped %s: needs source.*, target.* and T_target_source.txt" % name, file=sys.stderr)
    return pairs


def run_conform(cmd, timeout):
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
        code, out, err = p.returncode, p.stdout.decode("utf-8", "replace"), p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        code = "timeout"
        out = (e.stdout or b"").decode("utf-8", "replace")
        err = (e.stderr or b"").decode("utf-8", "replace")
    return code, out, err, time.monotonic() - start


def parse_json(out):
    out = out.strip()
    if not out:
        return None
    try:
        return json.loads(out)
    except ValueError:
        i = out.find("{")
        try:
            return json.loads(out[i:]) if i >= 0 else None
        except ValueError:
            return None


def reasons_of(j, err):
    """The verdict's reasons and conform's own 'conform: ...' message, one string."""
    parts = []
    if j:
        v = j.get("verdict") or {}
        if isinstance(v, dict):
            parts.extend(str(r) for r in (v.get("reasons") or []))
            if not parts and v.get("summary"):
                parts.append(str(v["summary"]))
    for line in err.splitlines():
        if line.startswith("conform:"):
            msg = line[len("conform:"):].strip()
            if msg.endswith("...") or msg.startswith(("warning", "read ", "coarse", "icp", "normals", "write")):
                continue  # progress and warnings, not the failure message
            if msg and not any(r in msg for r in parts):
                parts.append(msg)
    return parts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__,
                                 allow_abbrev=False)
    ap.add_argument("conform", help="the conform binary")
    ap.add_argument("pairs", help="folder of pair folders")
    ap.add_argument("--truth-start", action="store_true",
                    help="start from the truth (source pre-moved by it) with --init none: is a right start kept?")
    ap.add_argument("--only", default="", help="comma-separated pair names")
    ap.add_argument("--units", default=None, help="override the pairs' units (default: each pair's 'units' file, else m)")
    ap.add_argument("--init", default=None, help="coarse start (default fpfh; none with --truth-start)")
    ap.add_argument("--timeout", type=float, default=1800.0, help="seconds per run before it is killed")
    ap.add_argument("--verbose", action="store_true", help="print each command and conform's stderr")
    ap.add_argument("--keep", default=None, help="folder to keep each pair's JSON and stderr in (NAME.json, NAME.err)")
    args, extra = ap.parse_known_args()
    extra = [a for a in extra if a != "--"]
    only = set(x for x in args.only.split(",") if x)
    pairs = list_pairs(args.pairs, only)
    if not pairs:
        sys.exit("no pairs under %s" % args.pairs)
    init = args.init or ("none" if args.truth_start else "fpfh")

    print("# conform: %s" % args.conform)
    print("# mode: %s; init %s; extra flags: %s" % ("truth start" if args.truth_start else "coarse search", init,
                                                  " ".join(extra) if extra else "(none)"))
    print("# right: rotation < 2 deg and translation < max(5 x the source's median spacing, 1 % of its diagonal)")
    if args.truth_start:
        header = "%-28s %8s %5s %9s %9s %8s %5s %6s %4s %7s" % ("pair", "points", "units", "moved deg", "moved mm",
                                                               "bound mm", "kept", "trust", "exit", "s")
    else:
        header = "%-28s %8s %5s %9s %9s %8s %5s %6s %4s %7s" % ("pair", "points", "units", "rot deg", "trans mm",
                                                               "bound mm", "right", "trust", "exit", "s")
    print(header)
    print("-" * len(header))
    sys.stdout.flush()

    counts = {"pairs": 0, "right": 0, "right_accepted": 0, "wrong_accepted": 0, "accepted": 0, "refused_right": 0}
    notes = []
    with tempfile.TemporaryDirectory(prefix="eval_real_pairs_") as tmp:
        for name, folder, src, tgt, truth_path in pairs:
            units = args.units
            if units is None:
                upath = os.path.join(folder, "units")
                units = open(upath).read().strip() if os.path.isfile(upath) else "m"
            scale = MM_PER_UNIT[units]
            truth = read_matrix(truth_path)
            pts = read_points(src)
            bound_mm = max(5.0 * median_spacing(pts), 0.01 * diagonal(pts)) * scale
            scan = src
            expected = scaled(truth, scale)
            if args.truth_start:
                scan = os.path.join(tmp, name + "_source_at_truth.ply")
                write_ply(scan, [apply(truth, p) for p in pts])
                expected = [[1.0 if i == k else 0.0 for k in range(4)] for i in range(4)]
            out_t = os.path.join(tmp, name + "_T.txt")
            if os.path.exists(out_t):
                os.remove(out_t)
            cmd = [args.conform, "align", "--scan", scan, "--reference", tgt, "--units", units, "--init", init,
                   "--json", "--out-transform", out_t] + extra
            if args.verbose:
                print("+ " + " ".join(cmd), file=sys.stderr)
            code, out, err, seconds = run_conform(cmd, args.timeout)
            if args.verbose and err:
                sys.stderr.write(err)
            j = parse_json(out)
            if args.keep:
                os.makedirs(args.keep, exist_ok=True)
                with open(os.path.join(args.keep, name + ".json"), "w") as f:
                    f.write(out)
                with open(os.path.join(args.keep, name + ".err"), "w") as f:
                    f.write(err)
            found = None
            if j and "T_ref_scan" in j:
                found = j["T_ref_scan"]
            elif os.path.isfile(out_t):
                found = read_matrix(out_t)
            trust = (j or {}).get("trust", "-") if j else "-"
            counts["pairs"] += 1
            accepted = code == 0
            counts["accepted"] += accepted
            if found is None:
                rot = trans = math.nan
                right = False
            else:
                rot, trans = pose_error(found, expected)
                right = rot < 2.0 and trans < bound_mm
            counts["right"] += right
            counts["right_accepted"] += right and accepted
            counts["wrong_accepted"] += (not right) and accepted
            counts["refused_right"] += right and not accepted
            print("%-28s %8d %5s %9.3f %9.2f %8.2f %5s %6s %4s %7.1f%s" % (
                name, len(pts), units, rot, trans, bound_mm, "yes" if right else "NO", trust, code, seconds,
                "   <-- WRONG AND ACCEPTED" if accepted and not right else ""))
            sys.stdout.flush()
            if not accepted or not right or trust == "check":
                why = reasons_of(j, err)
                if code not in (0, 1) and not j:
                    why.append("no JSON; stderr: " + " | ".join(err.strip().splitlines()[-3:]))
                state = "no pose" if found is None else ("right" if right else "wrong")
                notes.append("%s (%s, exit %s, trust %s): %s" % (name, state, code, trust,
                                                                 " / ".join(why) if why else "(no reason given)"))

    print("-" * len(header))
    if notes:
        print("verdicts (refused, wrong or 'check'):")
        for n in notes:
            print("  " + n)
        print("-" * len(header))
    kept = "kept" if args.truth_start else "right"
    print("%d pairs: %s %d, %s and accepted (exit 0) %d, wrong and accepted (exit 0) %d, accepted %d, "
          "%s but refused %d" % (counts["pairs"], kept, counts["right"], kept, counts["right_accepted"],
                                  counts["wrong_accepted"], counts["accepted"], kept, counts["refused_right"]))

if __name__ == "__main__":
    main()
