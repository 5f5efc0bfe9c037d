"""conform's Python jobs against the CLI's --json on the same inputs (1e-9), and the binding's own promises."""

import math
import threading

import numpy as np
import pytest

import conform
from conftest import cli, cli_json, as_python


def assert_same(python, cli_values, tol=1e-9, where="JSON"):
    """The CLI's JSON, key for key and item for item, numbers to tol (relative and absolute)."""
    if isinstance(cli_values, dict):
        assert isinstance(python, dict) and set(python) == set(cli_values), where
        for key in cli_values:
            assert_same(python[key], cli_values[key], tol, f"{where}.{key}")
    elif isinstance(cli_values, list):
        assert isinstance(python, list) and len(python) == len(cli_values), where
        for i, (got, expected) in enumerate(zip(python, cli_values)):
            assert_same(got, expected, tol, f"{where}[{i}]")
    elif isinstance(cli_values, float) and not isinstance(python, bool):
        assert python == pytest.approx(cli_values, rel=tol, abs=tol), where
    else:
        assert python == cli_values and type(python) is type(cli_values), where


def test_compare_matches_cli(tubes):
    expected = cli_json("compare", "--scan", tubes["scan"], "--reference", tubes["nominal"], "--tolerance", 0.3,
                        "--transform", tubes["transform"])
    r = conform.compare(str(tubes["scan"]), tubes["nominal"], tolerance=0.3, transform=tubes["transform"])
    assert_same(r.to_dict(), expected)
    assert r.T_ref_scan.shape == (4, 4)
    assert r.deviation_mm.shape == (r.points,) and r.closest_mm.shape == (r.points, 3)
    assert np.count_nonzero(~np.isnan(r.deviation_mm)) == r.matched
    assert np.sqrt(np.nanmean(r.deviation_mm**2)) == pytest.approx(r.rms_mm, rel=1e-12)


def test_compare_in_memory_inputs_give_the_file_numbers(tubes):
    by_path = conform.compare(tubes["scan"], tubes["nominal"], transform=tubes["transform"]).to_dict()
    scan, nominal = conform.read(tubes["scan"]), conform.read(tubes["nominal"])
    transform = np.loadtxt(tubes["transform"])
    for s, ref, t in [(scan, nominal, transform), (scan.points, (nominal.points, nominal.faces), transform)]:
        d = conform.compare(s, ref, transform=t).to_dict()
        assert d["scan"] is None and d["reference"] is None and d["transform"] is None
        for key in ("rms_mm", "mean_mm", "p95_abs_mm", "matched", "T_ref_scan", "reference_faces"):
            assert d[key] == by_path[key], key


def test_compare_takes_each_inputs_units_as_the_cli(tubes, tmp_path):
    """A scan in metres against a reference in mm: scan_units as --scan-units, the same deviations as all in mm."""
    scan_m = tmp_path / "scan_m.xyz"
    np.savetxt(scan_m, conform.read(tubes["scan"]).points / 1000.0, fmt="%.12g")
    expected = cli_json("compare", "--scan", scan_m, "--reference", tubes["nominal"], "--scan-units", "m",
                        "--transform", tubes["transform"])
    r = conform.compare(str(scan_m), tubes["nominal"], scan_units="m", transform=tubes["transform"])
    assert_same(r.to_dict(), expected)
    assert r.scan_units == "m" and r.reference_units == "mm" and r.units is None
    in_mm = conform.compare(tubes["scan"], tubes["nominal"], transform=tubes["transform"])
    assert r.rms_mm == pytest.approx(in_mm.rms_mm, rel=1e-6)
    # units sets both, reference_units overrides it for the reference.
    both = conform.compare(str(scan_m), tubes["nominal"], units="m", reference_units="mm", transform=tubes["transform"])
    assert both.rms_mm == pytest.approx(r.rms_mm, rel=1e-12)


def test_read_gives_views(tubes):
    g = conform.read(tubes["nominal"])
    assert g.points.shape == (len(g), 3) and g.faces.shape[1] == 3 and g.faces.dtype == np.int32
    assert not g.points.flags.owndata and g.points.base is not None
    assert g.normals.shape in ((0, 3), (len(g), 3))
    radius = np.hypot(g.points[:, 0], g.points[:, 1])
    np.testing.assert_allclose(radius, 50.0, atol=0.01)  # the generated tube's nominal radius


def test_fit_cylinder_matches_cli(tubes):
    expected = cli_json("fit-cylinder", "--input", tubes["scan"], "--seed", 2)
    r = conform.fit_cylinder(tubes["scan"], seed=2)
    assert_same(r.to_dict(), expected)
    assert r.ok and r.radius_mm == pytest.approx(50.0, abs=0.1)
    assert r.inlier.dtype == bool and np.count_nonzero(r.inlier) == r.inliers


def test_saddle_matches_cli(tmp_path):
    expected = cli_json("saddle", "--R", 100, "--r", 40, "--right-angle-pose-deg", 45, "--step-deg", 5)
    r = conform.saddle(R=100, r=40, right_angle_pose_deg=45, step_deg=5)
    assert_same(r.to_dict(), expected)
    assert r.position_mm.shape == (r.points, 3) and r.theta_rad[-1] == pytest.approx(2 * math.pi)
    expected = cli_json("saddle", "--R", 100, "--r", 60, "--pitch-deg", 60, "--offset", 10,
                        "--right-angle-pose-deg", 30, "--speed", 10, "--period", 0.04)
    assert_same(conform.saddle(R=100, r=60, pitch_deg=60, offset=10, right_angle_pose_deg=30, speed=10,
                               period=0.04).to_dict(), expected)


def test_pose_error_matches_cli(tubes, tmp_path):
    identity = tmp_path / "I.txt"
    identity.write_text("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n")
    expected = cli_json("pose-error", "--transform", tubes["transform"], "--transform", identity, "--units", "m")
    r = conform.pose_error(tubes["transform"], np.eye(4), units="m")
    d = r.to_dict()
    assert d["transform_b"] is None
    d["transform_b"] = str(identity)
    assert_same(d, expected)
    assert r.translation_mm == pytest.approx(1000 * math.sqrt(0.1**2 + 0.2**2 + 0.05**2), rel=1e-12)


def test_errors_carry_the_cli_message(tubes, tmp_path):
    missing = tmp_path / "missing.ply"
    code, _, stderr = cli("compare", "--scan", missing, "--reference", tubes["nominal"], check=False)
    assert code == 2
    with pytest.raises(conform.Error) as e:
        conform.compare(missing, tubes["nominal"])
    assert as_python(stderr.strip().splitlines()[-1]) == f"conform: error: {e.value}"
    with pytest.raises(conform.Error, match=r"\(N, 3\) array"):
        conform.compare(np.zeros((5, 2)), tubes["nominal"])
    with pytest.raises(conform.Error, match="tolerance"):
        conform.compare(tubes["scan"], tubes["nominal"], tolerance=-1.0)


def test_progress_and_gil(tubes):
    stages = []
    conform.compare(tubes["scan"], tubes["nominal"], progress=lambda stage, f: stages.append((stage, f)))
    assert ("deviation", 1.0) in stages and stages[0] == ("read scan", 0.0)

    # A Python thread keeps running while a job computes: the GIL is released (no progress callback here, which
    # would take it back).
    ticks, stop = [0], threading.Event()

    def spin():
        while not stop.is_set():
            ticks[0] += 1

    thread = threading.Thread(target=spin)
    thread.start()
    during = []
    try:
        # Up to five runs: on a loaded machine (ctest -j2 beside other builds) the spinning thread may get no core
        # for the length of one run; with the GIL held it could never tick during any of them.
        for _ in range(5):
            before = ticks[0]
            conform.fit_cylinder(tubes["scan"], seed=1)
            during.append(ticks[0] - before)
            if during[-1] > 1000:
                break
    finally:
        stop.set()
        thread.join()
    assert max(during) > 1000, during

    def fail(stage, fraction):
        raise KeyboardInterrupt("stop")

    with pytest.raises(KeyboardInterrupt):
        conform.compare(tubes["scan"], tubes["nominal"], progress=fail)


def test_weld_layers_matches_cli(tmp_path):
    eroded = tmp_path / "blade.csv"
    cli("generate", "eroded", "--out", eroded)
    common = ["--bead-spacing", 3, "--layer-height", 1, "--chord-error", 0.05, "--torch-distance", 10]
    expected = cli_json("weld-layers", "--eroded", eroded, "--reference", tmp_path / "blade.reference.csv", *common)
    r = conform.weld_layers(eroded, reference=tmp_path / "blade.reference.csv", bead_spacing=3, layer_height=1,
                            chord_error=0.05, torch_distance=10)
    assert_same(r.to_dict(), expected)
    assert r.ok and r.points_mm.shape == (len(r.layer), 3) and set(r.layer) == set(range(1, r.layers + 1))
    expected = cli_json("weld-layers", "--eroded", eroded, "--reference-from-border", "--bias", "keep", *common)
    r = conform.weld_layers(eroded, reference_from_border=True, bias="keep", bead_spacing=3, layer_height=1,
                            chord_error=0.05, torch_distance=10)
    assert_same(r.to_dict(), expected)
    expected = cli_json("weld-layers", "--eroded", eroded, "--reference", tmp_path / "blade.reference.csv", *common,
                        "--bead-width", 3.6, "--max-overlap", 4)
    r = conform.weld_layers(eroded, reference=tmp_path / "blade.reference.csv", bead_spacing=3, layer_height=1,
                            chord_error=0.05, torch_distance=10, bead_width=3.6, max_overlap=4)
    assert_same(r.to_dict(), expected)
    with pytest.raises(conform.Error, match="reference_from_border"):
        conform.weld_layers(eroded, bead_spacing=3, layer_height=1, chord_error=0.05)


def test_profile_matches_cli(tmp_path):
    edge = tmp_path / "profile.csv"
    cli("generate", "profile", "--out", edge, "--kink-deg", 0.5, "--seed", 8)
    features = tmp_path / "profile.features.csv"
    for flags, kwargs in [([], {}), (["--model", "cubic", "--web-normal", "0,0.1,1"],
                                     {"model": "cubic", "web_normal": [0, 0.1, 1]})]:
        expected = cli_json("profile", "--edge", edge, "--features", features, *flags)
        r = conform.profile(edge, features, **kwargs)
        assert_same(r.to_dict(), expected)
        assert r.points_mm.shape == (sum(f["points"] for f in r.features), 3)
        assert r.feature.max() == len(r.features) - 1
    with pytest.raises(conform.Error, match="model"):
        conform.profile(edge, features, model="quintic")


def test_tube_joint_matches_cli(tmp_path):
    leg, stub = tmp_path / "leg.ply", tmp_path / "stub.ply"
    cli("generate", "tube-joint", "--out-leg", leg, "--out-stub", stub, "--out-truth", tmp_path / "truth.csv",
        "--pitch-deg", 45, "--offset", 100, "--ovality-pct", 1, "--peaking", 3, "--noise", 0.2, "--edge", 10)
    joint = ["--pitch-deg", 45, "--offset", 100, "--protrusion", 2014.2135623730949]
    timing = ("intersection_s", "total_s")  # wall-clock seconds, different in every run
    for flags, kwargs in [([], {}), (["--groove-deg", "30,40,50,40", "--wall-thickness", "20,10", "--step-mm", 10],
                                     {"groove_deg": [30, 40, 50, 40], "wall_thickness": [20, 10], "step_mm": 10}),
                          (["--weld-tolerance", 0.02, "--max-direction-error", 3],
                           {"weld_tolerance": 0.02, "max_direction_error": 3})]:
        expected = cli_json("tube-joint", "--leg", leg, "--stub", stub, *joint, *flags)
        r = conform.tube_joint(leg, stub, pitch_deg=45, offset=100, protrusion=2014.2135623730949, **kwargs)
        got = r.to_dict()
        for key in timing:
            got[key], expected[key] = 0.0, 0.0
        assert_same(got, expected)
        if not flags:  # the second joint's walls put a tool inside material: ok false, as the CLI's exit 1
            assert r.ok and r.points_mm.shape == (r.points, 3) and r.cut_directions.shape == (r.points, 3)
    with pytest.raises(conform.Error, match="protrusion"):
        conform.tube_joint(leg, stub, pitch_deg=45, offset=100)
    with pytest.raises(TypeError, match="protrusoin"):
        conform.tube_joint(leg, stub, protrusoin=1.0)


def test_generate_tube_matches_cli(tmp_path):
    flags = ["--radius", 40, "--length", 60, "--arc-deg", 120, "--vertices", 1500, "--ovality", 0.3, "--bump",
             "10,5,0.4,8", "--hole", "-20,0,4", "--noise", 0.01, "--noise-type", "uniform", "--seed", 5,
             "--axis-direction", "0,1,1", "--double"]
    expected = cli_json("generate", "tube", "--out", tmp_path / "cli.ply", *flags, "--quiet")
    r = conform.generate_tube(tmp_path / "py.ply", radius=40, length=60, arc_deg=120, vertices=1500, ovality=0.3,
                              bump=[[10, 5, 0.4, 8]], hole=[[-20, 0, 4]], noise=0.01, noise_type="uniform", seed=5,
                              axis_direction=[0, 1, 1], double=True)
    got = r.to_dict()
    for key in ("mesh", "truth_file"):
        assert got[key] == expected[key].replace("cli.", "py.")
        got[key] = expected[key]
    assert got["truth"]["mesh_file"] == "py.ply"
    got["truth"]["mesh_file"] = expected["truth"]["mesh_file"]
    assert_same(got, expected)
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()
    with pytest.raises(conform.Error, match="noise_type"):
        conform.generate_tube(tmp_path / "x.ply", noise_type="pink")
