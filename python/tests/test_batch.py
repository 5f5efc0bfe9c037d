"""conform.batch on a LocalCluster (2 worker processes): results identical to one-by-one, failures isolated, resume;
and the checks of issue 32 (outputs, resume key, isolation, timeout, special files)."""

import csv
import json
import os
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import conform
from conform import batch

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_batch_matches_one_by_one_and_resumes(tubes, tmp_path, client):
    d = tubes["dir"]
    manifest = tmp_path / "parts.csv"
    rows = [
        ["id", "job", "scan", "reference", "transform", "tolerance", "out_deviation", "input", "seed"],
        ["p1", "compare", os.path.relpath(tubes["scan"], tmp_path), str(tubes["nominal"]), "", "0.3", "", "", ""],
        ["p2", "compare", str(tubes["scan"]), str(tubes["nominal"]), str(tubes["transform"]), "0.1", "p2.ply", "", ""],
        ["bad", "compare", str(d / "missing.ply"), str(tubes["nominal"]), "", "", "", "", ""],
        ["cyl", "fit_cylinder", "", "", "", "", "", str(tubes["scan"]), "4"],
        ["al", "align", str(tubes["scan"]), str(tubes["nominal"]), "", "", "", "", ""],
    ]
    with open(manifest, "w", newline="") as f:
        csv.writer(f).writerows(rows)
    out = tmp_path / "out"
    summary = batch.run_batch(str(manifest), str(out), client)

    aligned = conform.align(tubes["scan"], tubes["nominal"])
    assert [r["id"] for r in summary] == ["p1", "p2", "bad", "cyl", "al"]
    assert [r["ok"] for r in summary] == [True, True, False, True, aligned.converged], summary[4]
    assert "missing.ply" in summary[2]["error"] and (out / "bad.error.txt").exists()
    assert not (out / "bad.json").exists()
    assert (out / "p2.ply").exists()
    one_by_one = {
        "p1": conform.compare(tubes["scan"], tubes["nominal"], tolerance=0.3),
        "p2": conform.compare(tubes["scan"], tubes["nominal"], transform=tubes["transform"], tolerance=0.1,
                              out_deviation=out / "p2.ply"),
        "cyl": conform.fit_cylinder(tubes["scan"], seed=4),
        "al": aligned,
    }
    for part, result in one_by_one.items():
        written = json.loads((out / f"{part}.json").read_text())
        expected = result.to_dict()
        if part == "p1":
            written["scan"] = expected["scan"]  # given relative to the manifest there
        assert written == expected, part
    with open(out / "summary.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert [r["id"] for r in table] == ["p1", "p2", "bad", "cyl", "al"]
    assert table[4]["trust"] == aligned.trust
    assert float(table[0]["rms_mm"]) == one_by_one["p1"].rms_mm

    # Resume: done parts are not run again (their files untouched), the failed one is retried.
    stamp = (out / "p1.json").stat().st_mtime_ns
    again = batch.run_batch(str(manifest), str(out), client)
    assert (out / "p1.json").stat().st_mtime_ns == stamp
    assert [r["ok"] for r in again] == [True, True, False, True, aligned.converged]


# Issue 32: outputs confined to --out-dir and never shared, the resume keyed on the part's job, options and inputs,
# each part in a process of its own (a crash or a timeout fails that part only), special files never opened.
HELPER = [sys.executable, str(Path(__file__).with_name("batch_part_helper.py"))]


def _manifest(path, rows):
    with open(path, "w", newline="") as f:
        csv.writer(f).writerows(rows)
    return str(path)


@pytest.fixture
def scan(tubes, tmp_path):
    """A copy of the tube scan the test may touch."""
    copy = tmp_path / "scan.ply"
    shutil.copyfile(tubes["scan"], copy)
    return copy


@pytest.mark.parametrize("cell", ["../x.ply", "sub/../../x.ply", "ABS/abs.ply", "up/x.ply", "/etc/hostname"])
def test_outputs_stay_in_out_dir(tubes, scan, tmp_path, cell):
    out = tmp_path / "out"
    out.mkdir()
    (out / "up").symlink_to(tmp_path, target_is_directory=True)  # a link out of DIR
    cell = cell.replace("ABS", str(tmp_path))
    for column in ("out_deviation", "report"):
        manifest = _manifest(tmp_path / "parts.csv", [["id", "job", "scan", "reference", column],
                                                      ["p1", "compare", str(scan), str(tubes["nominal"]), cell]])
        with pytest.raises(ValueError, match=f"part p1: {column}=.*(absolute|'\\.\\.'|outside --out-dir)"):
            batch.run_batch(manifest, str(out), None)
        assert sorted(p.name for p in out.iterdir()) == ["up"]  # nothing ran
        assert not (tmp_path / "x.ply").exists() and not (tmp_path / "abs.ply").exists()


def test_outputs_are_not_shared_nor_the_batch_files(tubes, scan, tmp_path):
    out = tmp_path / "out"
    header = ["id", "job", "scan", "reference", "out_deviation"]
    cases = [
        ([["p1", "compare", str(scan), str(tubes["nominal"]), "same.ply"],
          ["p2", "compare", str(scan), str(tubes["nominal"]), "same.ply"]], "part p1 writes it too"),
        ([["p1", "compare", str(scan), str(tubes["nominal"]), "./sub/../same.ply"],
          ["p2", "compare", str(scan), str(tubes["nominal"]), "same.ply"]], "'\\.\\.'"),
        ([["p1", "compare", str(scan), str(tubes["nominal"]), "p2.json"],
          ["p2", "compare", str(scan), str(tubes["nominal"]), ""]], "is p2.json, which the batch writes itself"),
        ([["p1", "compare", str(scan), str(tubes["nominal"]), "summary.csv"]], "is summary.csv"),
        ([["p1", "compare", str(scan), str(tubes["nominal"]), "p1.error.txt"]], "is p1.error.txt"),
        ([["p1", "compare", str(scan), str(tubes["nominal"]), ".conform-batch/p1.key"]], "in .conform-batch"),
        ([["p1", "compare", str(out / "d.ply"), str(tubes["nominal"]), ""],
          ["p2", "compare", str(scan), str(tubes["nominal"]), "d.ply"]], "is an input of part p1"),
    ]
    for rows, message in cases:
        manifest = _manifest(tmp_path / "parts.csv", [header] + rows)
        with pytest.raises(ValueError, match=message):
            batch.run_batch(manifest, str(out), None)
        assert not out.exists()  # refused before anything ran, DIR not even made
    # The manifest itself, kept in DIR.
    out.mkdir()
    manifest = _manifest(out / "parts.csv", [header, ["p1", "compare", str(scan), str(tubes["nominal"]), "parts.csv"]])
    with pytest.raises(ValueError, match="is the manifest"):
        batch.run_batch(manifest, str(out), None)
    # And the job's own check: an output that is the part's input (here through a hard link in DIR).
    os.link(scan, out / "alias.ply")
    manifest = _manifest(tmp_path / "parts.csv", [header, ["p1", "compare", str(scan), str(tubes["nominal"]),
                                                           "alias.ply"]])
    before = scan.read_bytes()
    rows = batch.run_batch(manifest, str(out), None)
    assert not rows[0]["ok"] and "this output is the input" in rows[0]["error"]
    assert scan.read_bytes() == before


def test_resume_recomputes_when_options_or_inputs_change(tubes, scan, tmp_path):
    out = tmp_path / "out"

    def run(tolerance):
        manifest = _manifest(tmp_path / "parts.csv", [["id", "job", "scan", "reference", "tolerance"],
                                                      ["p1", "compare", "scan.ply", str(tubes["nominal"]), tolerance]])
        rows = batch.run_batch(manifest, str(out), None)
        assert rows[0]["ok"], rows
        return json.loads((out / "p1.json").read_text()), (out / "p1.json").stat().st_mtime_ns

    first, stamp = run("0.3")
    assert first["tolerance_mm"] == 0.3
    assert run("0.3")[1] == stamp  # same job, options, inputs: resumed
    changed, stamp2 = run("0.1")  # the old resume returned the 0.3 result here
    assert changed["tolerance_mm"] == 0.1 and stamp2 != stamp
    os.utime(scan, ns=(scan.stat().st_atime_ns, scan.stat().st_mtime_ns + 10**9))  # the scan replaced
    assert run("0.1")[1] != stamp2
    (out / "p1.json").unlink()  # a JSON without its result: run again
    assert run("0.1")[0] == changed


def test_special_resume_files_are_not_opened(tubes, scan, tmp_path):
    out = tmp_path / "out"
    (out / batch.STATE_DIR).mkdir(parents=True)
    os.mkfifo(out / "p1.json")
    os.mkfifo(out / batch.STATE_DIR / "p2.key")
    (out / "p3.json").symlink_to(scan)
    rows = [["id", "job", "scan", "reference"]] + [[p, "compare", str(scan), str(tubes["nominal"])]
                                                   for p in ("p1", "p2", "p3")]
    manifest = _manifest(tmp_path / "parts.csv", rows)
    result = batch.run_batch(manifest, str(out), None)  # hung on p1.json before
    assert [r["ok"] for r in result] == [True, True, True]
    for p in ("p1", "p2", "p3"):
        assert stat.S_ISREG(os.lstat(out / f"{p}.json").st_mode) and json.loads((out / f"{p}.json").read_text())
    assert scan.read_bytes() == Path(tubes["scan"]).read_bytes()  # the link replaced, not its target


def test_a_crashing_part_fails_alone_on_one_worker(tubes, scan, tmp_path):
    rows = [["id", "job", "scan", "reference"]] + [[p, "compare", str(scan), str(tubes["nominal"])]
                                                   for p in ("crash", "good")]
    manifest = _manifest(tmp_path / "parts.csv", rows)
    out = tmp_path / "out"
    cluster = distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            crash, good = batch.run_batch(manifest, str(out), client, part_command=HELPER)
    finally:
        cluster.close()
    assert good["ok"] and (out / "good.json").exists(), good
    assert not crash["ok"] and "SIGSEGV" in crash["error"], crash
    assert "SIGSEGV" in (out / "crash.error.txt").read_text() and not (out / "crash.json").exists()


def test_a_part_past_its_timeout_is_killed(tubes, scan, tmp_path):
    rows = [["id", "job", "scan", "reference"]] + [[p, "compare", str(scan), str(tubes["nominal"])]
                                                   for p in ("hang", "good")]
    manifest = _manifest(tmp_path / "parts.csv", rows)
    out = tmp_path / "out"
    hang, good = batch.run_batch(manifest, str(out), None, part_timeout=1.5, part_command=HELPER)
    assert good["ok"]
    assert not hang["ok"] and "timed out after 1.5 s" in hang["error"]
    assert "timed out" in (out / "hang.error.txt").read_text()


def _command_line(*args):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    return subprocess.run([sys.executable, "-m", "conform.batch", *map(str, args)], capture_output=True, text=True,
                          env=env)


def test_command_line_states_the_timeout_and_refuses_a_bad_manifest_at_once(tubes, tmp_path):
    done = _command_line("--help")
    assert done.returncode == 0
    assert "--part-timeout SECONDS" in done.stdout and "default: 3600 s" in done.stdout
    manifest = _manifest(tmp_path / "parts.csv", [["id", "job", "scan", "reference", "out_deviation"],
                                                  ["p1", "compare", tubes["scan"], tubes["nominal"], "../p1.ply"]])
    done = _command_line(manifest, "--out-dir", tmp_path / "out", "--part-timeout", 5)
    assert done.returncode == 2, done.stderr
    assert "conform.batch: error: part p1: out_deviation='../p1.ply': '..' leaves --out-dir" in done.stderr
    assert not (tmp_path / "out").exists()  # refused before any cluster or part
    assert _command_line(manifest, "--out-dir", tmp_path / "out", "--part-timeout", -1).returncode == 2
