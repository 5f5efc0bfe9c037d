"""conform.batch on a LocalCluster (2 worker processes): results identical to one-by-one, failures isolated, resume."""

import csv
import json
import os

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
