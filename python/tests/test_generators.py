"""conform.generate_* against `conform generate ... --json` with the same flags: the same JSON, the same file bytes."""

import json

import pytest

import conform
from conftest import cli_json
from test_jobs import assert_same


def test_generate_eroded_matches_cli(tmp_path):
    for flags, kwargs in [([], {}),
                          (["--crater", "5,3,10,1.5,2", "--crater", "-10,0,8,1,0,0.3,2", "--bump", "20,5,4,0.5",
                            "--rows", 31, "--cols", 45, "--twist", 0.001, "--reference-offset", 0.1,
                            "--reference-tilt-deg", 0.2, "--noise", 0.02, "--seed", 7],
                           {"crater": [[5, 3, 10, 1.5, 2], [-10, 0, 8, 1, 0, 0.3, 2]], "bump": [[20, 5, 4, 0.5]],
                            "rows": 31, "cols": 45, "twist": 0.001, "reference_offset": 0.1,
                            "reference_tilt_deg": 0.2, "noise": 0.02, "seed": 7})]:
        expected = cli_json("generate", "eroded", "--out", tmp_path / "cli.csv", *flags)
        r = conform.generate_eroded(tmp_path / "py.csv", **kwargs)
        got = r.to_dict()
        for key in ("eroded", "reference", "rims"):
            assert got[key] == expected[key].replace("cli.", "py.")
            assert open(got[key], "rb").read() == open(expected[key], "rb").read(), key
            got[key] = expected[key]
        assert_same(got, expected)
    with pytest.raises(conform.Error, match="crater"):
        conform.generate_eroded(tmp_path / "bad.csv", crater=[[1, 2, 3]])


def test_generate_profile_matches_cli(tmp_path):
    for flags, kwargs in [([], {}),
                          (["--kink-deg", 0.5, "--twist-deg", 1.5, "--bow-asymmetry", 0.3, "--second-edge",
                            "--marking-line", "--outliers", 3, "--dropouts", 0.05, "--offset", "100,-50,10",
                            "--reverse", "--seed", 8, "--holes", 3, "--length", 3000, "--kink-at", 1000, "--spacing", 10],
                           {"kink_deg": 0.5, "twist_deg": 1.5, "bow_asymmetry": 0.3, "second_edge": True,
                            "marking_line": True, "outliers": 3, "dropouts": 0.05, "offset": [100, -50, 10],
                            "reverse": True, "seed": 8, "holes": 3, "length": 3000, "kink_at": 1000, "spacing": 10})]:
        if "--length" not in flags:
            flags, kwargs = flags + ["--length", 2000], dict(kwargs, length=2000)
        expected = cli_json("generate", "profile", "--out", tmp_path / "cli.csv", *flags)
        got = conform.generate_profile(tmp_path / "py.csv", **kwargs).to_dict()
        for key in [k for k in expected if k.endswith("_path") and expected[k] is not None]:
            assert got[key] == expected[key].replace("cli.", "py.")
            if key != "truth_json_path":  # the truth JSON names its own files
                assert open(got[key], "rb").read() == open(expected[key], "rb").read(), key
        for key in [k for k in expected if isinstance(expected[k], str) and "cli." in expected[k]]:
            assert got[key] == expected[key].replace("cli.", "py."), key  # the files it names, as the CLI's
            got[key] = expected[key]
        assert_same(got, expected)
    with pytest.raises(conform.Error, match="kink_at_mm"):
        conform.generate_profile(tmp_path / "bad.csv", length=3000, kink_deg=1)


def test_generate_plate_and_nosecone_match_cli(tmp_path):
    small = ["--scan-points", 4000, "--contour-spacing", 2, "--surface-edge", 4, "--quiet"]
    cases = [("plate", ["--opening", "rectangle", "--corner-radius", 10, "--missing", 0.1, "--holes", 2, "--field",
                        0.5, "--seed", 3, "--sag", 2],
              {"opening": "rectangle", "corner_radius": 10, "missing": 0.1, "holes": 2, "field": 0.5, "seed": 3,
               "sag": 2}),
             ("nosecone", ["--ovality", 2, "--droop", 3, "--noise", 0.03], {"ovality": 2, "droop": 3,
                                                                          "noise": 0.03})]
    for shape, flags, kwargs in cases:
        expected = cli_json("generate", shape, "--out", tmp_path / f"cli_{shape}.ply", *small, *flags)
        kwargs = dict({"scan_points": 4000, "contour_spacing": 2, "surface_edge": 4}, **kwargs)
        got = getattr(conform, f"generate_{shape}")(tmp_path / f"py_{shape}.ply", **kwargs).to_dict()
        for key in ("scan", "nominal", "contour", "trajectory", "truth_trajectory", "truth_file"):
            assert got[key] == expected[key].replace("/cli_", "/py_")
            if key != "truth_file":  # the truth JSON names its own files
                assert open(got[key], "rb").read() == open(expected[key], "rb").read(), key
        # The file names (also in the truth's own list) are the only difference.
        assert_same(json.loads(json.dumps(got).replace("py_", "cli_")), expected)
    with pytest.raises(TypeError, match="sag"):
        conform.generate_nosecone(tmp_path / "x.ply", sag=2)
    with pytest.raises(conform.Error, match="opening"):
        conform.generate_plate(tmp_path / "x.ply", opening="circle")


def test_generate_tube_joint_matches_cli(tmp_path):
    flags = ["--pitch-deg", 45, "--offset", 100, "--ovality-pct", 1, "--peaking", 3, "--noise", 0.2, "--edge", 20,
             "--leg-bump", "10,50,2,40", "--stub-bump", "200,-30,1,30", "--leg-arc-deg", 120, "--seed", 4, "--ascii"]
    names = {who: [tmp_path / f"{who}_{part}" for part in ("leg.ply", "stub.ply", "truth.csv")] for who in ("cli", "py")}
    expected = cli_json("generate", "tube-joint", "--out-leg", names["cli"][0], "--out-stub", names["cli"][1],
                        "--out-truth", names["cli"][2], *flags)
    r = conform.generate_tube_joint(*names["py"], pitch_deg=45, offset=100, ovality_pct=1, peaking=3, noise=0.2,
                                    edge=20, leg_bump=[[10, 50, 2, 40]], stub_bump=[[200, -30, 1, 30]],
                                    leg_arc_deg=120, seed=4, ascii=True)
    got = r.to_dict()
    for key, mine, theirs in zip(("leg", "stub", "truth"), names["py"], names["cli"]):
        assert got[key] == str(mine) and expected[key] == str(theirs)
        assert mine.read_bytes() == theirs.read_bytes(), key
        got[key] = expected[key]
    assert_same(got, expected)
    with pytest.raises(TypeError, match="pitch"):
        conform.generate_tube_joint(*names["py"], pitch=45)
