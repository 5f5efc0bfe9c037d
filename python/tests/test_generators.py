"""conform.generate_* against `conform generate ... --json` with the same flags: the same JSON, the same file bytes."""

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
    with pytest.raises(conform.Error, match="--crater"):
        conform.generate_eroded(tmp_path / "bad.csv", crater=[[1, 2, 3]])
