"""report= on every job that has the CLI's --report: the same page, byte for byte, as `conform <job> --report`
(CONFORM_REPORT_DATE fixes the date both show); a path that is not .html is refused before any work."""

import json
import re

import pytest

import conform
from conftest import cli


@pytest.fixture(autouse=True)
def fixed_date(monkeypatch):
    monkeypatch.setenv("CONFORM_REPORT_DATE", "2026-01-01 00:00 UTC")


def embedded_json(page):
    found = re.search(r'<script type="application/json" id="conform-result">(.*?)</script>', page, re.S)
    assert found, "no embedded result"
    return json.loads(found.group(1))


def same_page(tmp_path, job, cli_args, call):
    """Runs the CLI with --report and the Python call with report=; both pages must be the same bytes."""
    cli_page, py_page = tmp_path / f"{job}.cli.html", tmp_path / f"{job}.py.html"
    code, _, err = cli(job, *cli_args, "--report", cli_page, check=False)
    assert code in (0, 1), f"conform {job} exit {code}: {err}"
    result = call(py_page)
    assert py_page.read_bytes() == cli_page.read_bytes(), job
    assert embedded_json(py_page.read_text()) == json.loads(json.dumps(result.to_dict()))
    return result


def test_measuring_jobs_write_the_cli_page(tubes, tmp_path):
    scan, nominal = str(tubes["scan"]), str(tubes["nominal"])
    same_page(tmp_path, "align", ["--scan", scan, "--reference", nominal],
              lambda page: conform.align(scan, nominal, report=page))
    same_page(tmp_path, "compare", ["--scan", scan, "--reference", nominal, "--tolerance", 0.1],
              lambda page: conform.compare(scan, nominal, tolerance=0.1, report=page))
    r = same_page(tmp_path, "fit-cylinder", ["--input", scan, "--seed", 2, "--points", "vertices"],
                  lambda page: conform.fit_cylinder(scan, seed=2, points="vertices", report=page))
    assert r.ok and r.radius_mm == pytest.approx(50.0, abs=0.1)
    same_page(tmp_path, "saddle", ["--R", 100, "--r", 40, "--right-angle-pose-deg", 45, "--step-deg", 5],
              lambda page: conform.saddle(R=100, r=40, right_angle_pose_deg=45, step_deg=5, report=page))


def test_fit_cylinder_points_choice_matches_cli(tubes):
    for points in ("vertices", "surface"):
        code, out, _ = cli("fit-cylinder", "--input", tubes["scan"], "--seed", 2, "--points", points,
                           "--surface-samples", 5000, "--json", check=False)
        assert code in (0, 1)
        r = conform.fit_cylinder(tubes["scan"], seed=2, points=points, surface_samples=5000)
        assert r.to_dict() == json.loads(out), points
    with pytest.raises(conform.Error, match="points"):
        conform.fit_cylinder(tubes["scan"], points="faces")


def test_path_jobs_write_the_cli_page(tmp_path):
    eroded = tmp_path / "blade.csv"
    cli("generate", "eroded", "--out", eroded)
    weld = {"bead_spacing": 3, "layer_height": 1, "chord_error": 0.05}
    same_page(tmp_path, "weld-layers", ["--eroded", eroded, "--reference-from-border", "--bead-spacing", 3,
                                        "--layer-height", 1, "--chord-error", 0.05],
              lambda page: conform.weld_layers(eroded, reference_from_border=True, report=page, **weld))
    edge = tmp_path / "profile.csv"
    cli("generate", "profile", "--out", edge, "--seed", 8)
    features = tmp_path / "profile.features.csv"
    same_page(tmp_path, "profile", ["--edge", edge, "--features", features],
              lambda page: conform.profile(edge, features, report=page))
    d = tmp_path
    cli("generate", "plate", "--out", d / "p.ply", "--scan-points", 8000, "--contour-spacing", 2, "--surface-edge", 4,
        "--quiet")
    same_page(tmp_path, "sicp", ["--contour", d / "p.contour.csv", "--scan", d / "p.ply", "--trajectory",
                                 d / "p.trajectory.csv", "--surface", d / "p.nominal.ply"],
              lambda page: conform.sicp(d / "p.contour.csv", d / "p.ply", d / "p.trajectory.csv",
                                        surface=d / "p.nominal.ply", report=page))


def test_tube_joint_page_embeds_its_result(tmp_path):
    # Its JSON holds the run's wall-clock seconds, so its page is checked against its own result, not the CLI's.
    leg, stub = tmp_path / "leg.ply", tmp_path / "stub.ply"
    cli("generate", "tube-joint", "--out-leg", leg, "--out-stub", stub, "--out-truth", tmp_path / "truth.csv",
        "--pitch-deg", 45, "--offset", 100, "--edge", 10)
    page = tmp_path / "joint.html"
    r = conform.tube_joint(leg, stub, pitch_deg=45, offset=100, protrusion=2014.2135623730949, report=page)
    assert r.ok and embedded_json(page.read_text()) == json.loads(json.dumps(r.to_dict()))


def test_a_report_that_is_not_html_is_refused_before_any_work(tubes, tmp_path):
    page = tmp_path / "report.txt"
    with pytest.raises(conform.Error, match="must be .html"):
        conform.align(tubes["scan"], tubes["nominal"], report=page)
    with pytest.raises(conform.Error, match="must be .html"):
        conform.tube_joint(tubes["scan"], tubes["nominal"], report=page)
    assert not page.exists()
