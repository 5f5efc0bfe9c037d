"""conform.align (and the other registration jobs) against the CLI's --json on the same inputs (1e-9)."""

import numpy as np
import pytest

import conform
from conftest import cli, cli_json, as_python
from test_jobs import assert_same


def test_align_matches_cli(tubes, tmp_path):
    # The scan roughly in place (init none, the default method for a mesh), then the CLI's every flag changed.
    expected = cli_json("align", "--scan", tubes["scan"], "--reference", tubes["nominal"])
    r = conform.align(tubes["scan"], tubes["nominal"])
    assert_same(r.to_dict(), expected)
    assert r.T_ref_scan.shape == (4, 4) and r.converged == (r.trust != "no")
    flags = ["--method", "point-to-plane", "--max-distance", 5, "--overlap", 0.9, "--max-iterations", 30,
             "--free-tolerance-mm", 0.05, "--free-tolerance-deg", 0.02, "--max-noise-ratio", 10,
             "--out-transform", tmp_path / "cli.T.txt"]
    expected = cli_json("align", "--scan", tubes["scan"], "--reference", tubes["nominal"], *flags)
    r = conform.align(tubes["scan"], tubes["nominal"], method="point-to-plane", max_distance=5, overlap=0.9,
                      max_iterations=30, free_tolerance_mm=0.05, free_tolerance_deg=0.02, max_noise_ratio=10,
                      out_transform=tmp_path / "py.T.txt")
    got = r.to_dict()
    assert got["transform_file"] == expected["transform_file"].replace("cli.", "py.")
    got["transform_file"] = expected["transform_file"]
    assert_same(got, expected)
    if r.converged:
        assert (tmp_path / "py.T.txt").read_bytes() == (tmp_path / "cli.T.txt").read_bytes()


def test_align_fpfh_and_in_memory_inputs(tmp_path):
    # A patch with a bump (so FPFH has a feature), moved off the nominal by the generator's axis point.
    nominal, scan = tmp_path / "nominal.ply", tmp_path / "scan.ply"
    cli("generate", "tube", "--out", nominal, "--radius", 60, "--length", 80, "--arc-deg", 120, "--vertices", 1500,
        "--bump", "0,0,3,12", "--quiet")
    cli("generate", "tube", "--out", scan, "--radius", 60, "--length", 80, "--arc-deg", 120, "--vertices", 1200,
        "--bump", "0,0,3,12", "--axis-point", "4,-3,2", "--noise", 0.02, "--seed", 4, "--quiet")
    expected = cli_json("align", "--scan", scan, "--reference", nominal, "--init", "fpfh")
    r = conform.align(scan, nominal, init="fpfh")
    assert_same(r.to_dict(), expected)
    assert r.init == "fpfh" and len(r.starts) == len(expected["starts"])
    g, ref = conform.read(scan), conform.read(nominal)
    d = conform.align(g.points, (ref.points, ref.faces), init="fpfh").to_dict()
    for key in ("T_ref_scan", "rms_mm", "iterations", "trust", "scan_points", "reference_faces"):
        assert d[key] == r.to_dict()[key], key


def test_align_errors_carry_the_cli_message(tubes):
    code, _, stderr = cli("align", "--scan", tubes["scan"], "--reference", tubes["nominal"], "--init", "pairs:",
                          check=False)
    assert code == 2
    with pytest.raises(conform.Error) as e:
        conform.align(tubes["scan"], tubes["nominal"], init="pairs:")
    assert as_python(stderr.strip().splitlines()[-1]) == f"conform: error: {e.value}"
    with pytest.raises(conform.Error, match="method"):
        conform.align(tubes["scan"], tubes["nominal"], method="point-to-line")
    with pytest.raises(conform.Error, match="overlap"):
        conform.align(tubes["scan"], tubes["nominal"], overlap=1.5)


@pytest.fixture(scope="module")
def plate(tmp_path_factory):
    """A small generated plate (sicp's test data): scan, contour, nominal surface, trajectory and its truth."""
    d = tmp_path_factory.mktemp("plate")
    cli("generate", "plate", "--out", d / "p.ply", "--scan-points", 8000, "--contour-spacing", 2, "--surface-edge", 4,
        "--quiet")
    return {name: d / f"p.{name}" for name in ("ply", "contour.csv", "nominal.ply", "trajectory.csv", "truth.csv")}


def test_sicp_matches_cli(plate, tmp_path):
    common = ["--contour", plate["contour.csv"], "--scan", plate["ply"], "--trajectory", plate["trajectory.csv"],
              "--surface", plate["nominal.ply"], "--quiet"]
    expected = cli_json("sicp", *common, "--truth", plate["truth.csv"], "--out-trajectory", tmp_path / "cli.csv")
    r = conform.sicp(plate["contour.csv"], plate["ply"], plate["trajectory.csv"], surface=plate["nominal.ply"],
                     truth=plate["truth.csv"], out_trajectory=tmp_path / "py.csv")
    got = r.to_dict()
    assert got["out_trajectory"] == expected["out_trajectory"].replace("cli.", "py.")
    got["out_trajectory"] = expected["out_trajectory"]
    assert_same(got, expected)
    assert r.trusted and r.points_mm.shape == (r.trajectory_rows, 3) and r.normals.shape == (r.trajectory_rows, 3)
    written = np.loadtxt(tmp_path / "py.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(written[:, :3], r.points_mm, atol=1e-6)  # the CSV's printed digits
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    checks = {"max_corner_gap": 30, "max_edge_offset": 0.6, "max_row_step": 0.3, "max_off_surface": 0.1,
              "max_surface_offset": 0.5, "max_normal_error_deg": 2.5, "max_local_offset": 0.3,
              "max_dent_slope_deg": 3.5}
    flags = [x for k, v in checks.items() for x in ("--" + k.replace("_", "-"), v)]
    expected = cli_json("sicp", *common, *flags)
    got = conform.sicp(plate["contour.csv"], plate["ply"], plate["trajectory.csv"], surface=plate["nominal.ply"],
                       **checks).to_dict()
    assert_same(got, expected)

    flags = ["--model", "projection", "--projection-fit", "spline", "--normals", "scan", "--segment-length", 30,
             "--max-iterations", 20, "--min-edge-points", 5]
    expected = cli_json("sicp", *common, *flags)
    r = conform.sicp(plate["contour.csv"], conform.read(plate["ply"]), plate["trajectory.csv"],
                     surface=plate["nominal.ply"], model="projection", projection_fit="spline", normals="scan",
                     segment_length=30, max_iterations=20, min_edge_points=5)
    assert_same(r.to_dict(), expected)


def test_sicp_errors(plate):
    with pytest.raises(conform.Error, match="model"):
        conform.sicp(plate["contour.csv"], plate["ply"], plate["trajectory.csv"], model="affine")
    with pytest.raises(conform.Error, match="offset of the scanned surface"):
        conform.sicp(plate["contour.csv"], plate["ply"], plate["trajectory.csv"], surface=plate["nominal.ply"],
                     max_surface_offset=0)
    with pytest.raises(TypeError, match="segment_lenght"):
        conform.sicp(plate["contour.csv"], plate["ply"], plate["trajectory.csv"], segment_lenght=30)
