"""conform.export against `conform export --json` on the same path file: the same JSON and the same program bytes."""

import numpy as np
import pytest

import conform
from conftest import cli, cli_json, as_python
from test_jobs import assert_same


def test_export_matches_cli(tmp_path):
    path = tmp_path / "saddle.csv"
    cli("saddle", "--R", 100, "--r", 40, "--right-angle-pose-deg", 45, "--step-deg", 5, "--out", path)
    frame = np.array([[0, -1, 0, 500], [1, 0, 0, 200], [0, 0, 1, 800], [0, 0, 0, 1.0]])
    np.savetxt(tmp_path / "frame.txt", frame)
    for flags, kwargs in [([], {}),
                          (["--frame", tmp_path / "frame.txt", "--speed-mm-s", 20, "--approach-mm", 0, "--max-points",
                            30, "--roll-cone-deg", 20, "--preferred-x", "0,1,0", "--tool", "tool1"],
                           {"frame": frame, "speed_mm_s": 20, "approach_mm": 0, "max_points": 30,
                            "roll_cone_deg": 20, "preferred_x": [0, 1, 0], "tool": "tool1"})]:
        for fmt in ("rapid", "gcode"):
            expected = cli_json("export", "--path", path, "--format", fmt, "--out", tmp_path / f"cli_{fmt}.prg",
                                *flags, "--name", "seam")
            r = conform.export(path, format=fmt, out=tmp_path / f"py_{fmt}.prg", name="seam", **kwargs)
            got = r.to_dict()
            assert got["written"] == [w.replace("/cli_", "/py_") for w in expected["written"]]
            got["written"] = expected["written"]
            assert_same(got, expected)
            assert r.T_base_part.shape == (4, 4)
            for mine, theirs in zip(r.written, expected["written"]):
                assert open(mine, "rb").read() == open(theirs, "rb").read()
    with pytest.raises(conform.Error, match="format"):
        conform.export(path, format="kuka", out=tmp_path / "x.src")
    code, _, stderr = cli("export", "--path", path, "--format", "krl", "--out", tmp_path / "1bad.src", check=False)
    assert code == 2
    with pytest.raises(conform.Error) as e:
        conform.export(path, format="krl", out=tmp_path / "1bad.src")
    assert as_python(stderr.strip().splitlines()[-1]) == f"conform: error: {e.value}"


def test_export_takes_several_paths_as_the_cli(tmp_path):
    """A list of path files is one program in order, as the CLI's repeated --path."""
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    cli("saddle", "--R", 100, "--r", 40, "--right-angle-pose-deg", 45, "--step-deg", 5, "--out", a)
    cli("saddle", "--R", 120, "--r", 30, "--right-angle-pose-deg", 30, "--step-deg", 10, "--out", b)
    expected = cli_json("export", "--path", a, "--path", b, "--format", "rapid", "--out", tmp_path / "cli.mod",
                        "--name", "seams")
    r = conform.export([a, str(b)], format="rapid", out=tmp_path / "py.mod", name="seams")
    got = r.to_dict()
    got["written"] = expected["written"]
    assert_same(got, expected)
    assert r.segments == 2 and [p["job"] for p in r.paths] == ["saddle", "saddle"]
    assert open(tmp_path / "py.mod", "rb").read() == open(tmp_path / "cli.mod", "rb").read()
    with pytest.raises(conform.Error, match="at least one"):
        conform.export([], format="rapid", out=tmp_path / "none.mod")
