"""conform.inspect (issue 33): the same figures as `conform inspect --json`, on a generated half-turn scan of the bundled
IGES cylinder (R 15 x 40 mm) made 0.03 mm oversize, given as a file and as an array; tolerances judged; bad options
raise conform.Error naming the keyword argument."""

import pathlib

import numpy as np
import pytest

import conform
from conftest import cli, cli_json
from test_jobs import assert_same

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "datasets" / "examples"
CYLINDER = EXAMPLES / "cylinder.igs"
LIMITS = EXAMPLES / "cylinder.limits.csv"


@pytest.fixture(scope="module")
def scan(tmp_path_factory):
    """The cylinder's side, R 15.03 (0.03 mm oversize), noise 0.005 mm, as the generator writes it."""
    d = tmp_path_factory.mktemp("inspect")
    path = d / "scan.ply"
    cli("generate", "tube", "--out", path, "--radius", 15.03, "--length", 40, "--axis-point", "0,0,20", "--arc-deg",
        180, "--edge", 0.5, "--noise", 0.005, "--quiet")
    return path


def test_inspect_gives_the_clis_figures(tmp_path, scan):
    expected = cli_json("inspect", "--scan", scan, "--reference", CYLINDER, "--tolerances", LIMITS)
    r = conform.inspect(scan, CYLINDER, tolerances=LIMITS)
    assert_same(r.to_dict(), expected)
    side = r.faces[0]
    assert side["type"] == "cylinder" and side["deviation_to"] == "exact surface"
    assert side["radius_mm"] == pytest.approx(15.03, abs=0.002)  # the oversize, measured
    assert side["mean_mm"] == pytest.approx(0.03, abs=0.002)     # a shaft: material outside the CAD is +
    assert r.verdict == "pass"                                   # +-0.05, form 0.05
    assert r.point_face.shape == (r.points,) and set(np.unique(r.point_face)) <= {0, 1}
    assert (r.point_face == 1).sum() == side["points"]
    boss = r.features[0]  # the side as a feature: a boss of one face
    assert boss["kind"] == "boss" and boss["faces"] == [1] and boss["points"] == side["points"]
    assert boss["diameter_mm"] == pytest.approx(30.06, abs=0.004)


def test_inspect_takes_an_array_and_judges_tolerances(tmp_path, scan):
    points = conform.read(scan).points
    limits = tmp_path / "tight.csv"
    limits.write_text("face,lower_mm,upper_mm,form_mm\n1,-0.02,0.02,\n")
    r = conform.inspect(points, CYLINDER, tolerances=limits, report=tmp_path / "page.html")
    assert r.scan is None  # given in memory
    assert b"conform inspect" in (tmp_path / "page.html").read_bytes()
    assert r.verdict == "fail" and r.faces[0]["tolerance"]["profile_pass"] is False


def test_bad_options_name_the_keyword_argument(scan):
    with pytest.raises(conform.Error, match="max_distance"):
        conform.inspect(scan, CYLINDER, max_distance=-1.0)
    with pytest.raises(conform.Error, match="align"):
        conform.inspect(scan, CYLINDER, align="sideways")
    with pytest.raises(conform.Error, match="datums"):
        conform.inspect(scan, CYLINDER, datums=[7])


def test_batch_gives_each_face_and_feature_across_parts_with_their_capability(tmp_path):
    """Three parts 0.02, 0.03 and 0.04 mm oversize: face 1's mean deviation over the parts is 0.03 mm with a standard
    deviation of 0.01 (n - 1), so against +-0.05 Cp = 0.1 / 0.06 = 1.67 and Cpk = 0.02 / 0.03 = 0.67. The side as a
    feature (a boss of one face): diameters 30.04, 30.06, 30.08, s = 0.02, so against 29.9..30.1 Cp = 0.2 / 0.12 =
    1.67 and Cpk = 0.04 / 0.06 = 0.67."""
    from conform import batch

    limits = tmp_path / "limits.csv"
    limits.write_text("face,lower_mm,upper_mm,form_mm,diameter_lower_mm,diameter_upper_mm,position_mm\n"
                      "1,-0.05,0.05,0.05,29.9,30.1,0.05\n")

    # In the part frame (no best fit: over a half turn it would move the scan across the axis and take up part of
    # the oversize).
    rows = [["id", "job", "scan", "reference", "tolerances"]]
    for k, oversize in enumerate([0.02, 0.03, 0.04]):
        scan = tmp_path / f"scan{k}.ply"
        cli("generate", "tube", "--out", scan, "--radius", 15 + oversize, "--length", 40, "--axis-point", "0,0,20",
            "--arc-deg", 180, "--edge", 0.5, "--noise", 0.005, "--seed", k + 1, "--quiet")
        rows.append([f"part{k}", "inspect", scan.name, str(CYLINDER), str(limits)])
    manifest = tmp_path / "parts.csv"
    manifest.write_text("\n".join(",".join(r) for r in rows) + "\n")
    summary = batch.run_batch(manifest, tmp_path / "out", None)
    assert [r["ok"] for r in summary] == [True, True, True], summary
    with open(tmp_path / "out" / "inspect_faces.csv", newline="") as f:
        faces = {r["id"]: r for r in __import__("csv").DictReader(f)}
    side = faces["1"]
    assert side["type"] == "cylinder" and int(side["parts"]) == 3
    assert float(side["mean_mm"]) == pytest.approx(0.03, abs=0.001)
    assert float(side["std_mm"]) == pytest.approx(0.01, abs=0.001)
    assert float(side["radius_mean_mm"]) == pytest.approx(15.03, abs=0.001)
    assert float(side["cp"]) == pytest.approx(1.667, rel=0.1)
    assert float(side["cpk"]) == pytest.approx(0.667, rel=0.1)
    assert int(faces["2"]["parts"]) == 0 and faces["2"]["error"] == "no part measured it"  # a cap, never scanned
    with open(tmp_path / "out" / "inspect_features.csv", newline="") as f:
        features = list(__import__("csv").DictReader(f))
    assert len(features) == 1, features
    boss = features[0]
    assert boss["kind"] == "boss" and boss["faces"] == "1" and int(boss["fitted_parts"]) == 3
    assert float(boss["nominal_diameter_mm"]) == 30.0
    assert float(boss["mean_mm"]) == pytest.approx(float(side["mean_mm"]), abs=1e-12)  # one face: the face's figures
    assert float(boss["diameter_mean_mm"]) == pytest.approx(30.06, abs=0.002)
    assert float(boss["diameter_std_mm"]) == pytest.approx(0.02, abs=0.002)
    assert float(boss["diameter_min_mm"]) == pytest.approx(30.04, abs=0.002)
    assert float(boss["diameter_max_mm"]) == pytest.approx(30.08, abs=0.002)
    assert float(boss["cp"]) == pytest.approx(1.667, rel=0.1)
    assert float(boss["cpk"]) == pytest.approx(0.667, rel=0.1)
    assert float(boss["position_max_mm"]) < 0.01  # in the part frame, the axis where it should be
    assert float(boss["position_cpk"]) > 1.0
    assert boss["position_limit_mm"] == "0.05" and boss["diameter_lower_mm"] == "29.9"


def test_inspect_with_datums_gives_the_best_fit_beside_the_datum_frame():
    """The cylinder made 0.05 mm long at its bottom (the bottom cap at z = -0.05), scanned whole (side and both caps,
    a 0.5 mm grid, no noise). The datum frame of the bottom cap (primary only) puts that cap on its nominal: the top
    sits 0.05 mm out. The best fit beside it is align="best-fit" without datums, its pose and figures: it leaves about
    half of the 0.05 mm on each cap. (Its pose may differ by a turn about the axis, which changes no figure.)"""
    side = [(15 * np.cos(a), 15 * np.sin(a), z) for a in np.arange(0, 2 * np.pi, 0.5 / 15) for z in np.arange(1, 39.5, 0.5)]
    grid = [(x, y) for x in np.arange(-14.25, 14.3, 0.5) for y in np.arange(-14.25, 14.3, 0.5) if x * x + y * y < 14 ** 2]
    points = np.array(side + [(x, y, -0.05) for x, y in grid] + [(x, y, 40.0) for x, y in grid])
    aligned = conform.inspect(points, CYLINDER, align="best-fit", max_distance=1.0)
    assert "best_fit" not in aligned.faces[0] and "best_fit" not in aligned.to_dict()
    bottom = next(f["id"] for f in aligned.faces if f["type"] == "plane" and f["nominal"]["normal"][2] < -0.5)
    top = next(f["id"] for f in aligned.faces if f["type"] == "plane" and f["nominal"]["normal"][2] > 0.5)
    r = conform.inspect(points, CYLINDER, datums=[bottom], max_distance=1.0)
    b, t = r.faces[bottom - 1], r.faces[top - 1]
    assert b["mean_mm"] == pytest.approx(0.0, abs=0.002) and t["mean_mm"] == pytest.approx(0.05, abs=0.002)
    for face in (bottom, top):
        for key in ("points", "mean_mm", "std_mm", "min_mm", "max_mm", "form_mm"):
            assert r.faces[face - 1]["best_fit"][key] == pytest.approx(aligned.faces[face - 1][key], abs=1e-5)
    assert b["best_fit"]["mean_mm"] == pytest.approx(0.025, abs=0.003)  # not the datum frame's 0
    assert t["best_fit"]["mean_mm"] == pytest.approx(0.025, abs=0.003)  # nor its 0.05
    assert r.best_fit["converged"] and r.best_fit["pose"] == "--align best-fit on the scan as read"
    assert np.allclose(r.best_fit["T_ref_scan"], aligned.to_dict()["T_ref_scan"], atol=1e-9)
    assert r.features[0]["best_fit"]["diameter_mm"] == pytest.approx(30.0, abs=0.002)
