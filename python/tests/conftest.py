"""Shared fixtures: the conform executable (CONFORM_EXE, set by ctest) and generated tubes with known deformation."""

import json
import os
import re
import subprocess

import pytest


def conform_exe():
    exe = os.environ.get("CONFORM_EXE")
    if not exe:
        pytest.skip("CONFORM_EXE not set (run through ctest)")
    return exe


def cli(*args, check=True):
    """Run the CLI; returns (exit code, stdout, stderr)."""
    done = subprocess.run([conform_exe(), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"conform {' '.join(map(str, args))}: exit {done.returncode}: {done.stderr}")
    return done.returncode, done.stdout, done.stderr


def as_python(message):
    """A CLI message as the binding words it (python/src/inputs.h, for_python): --flag-name as flag_name."""
    return re.sub(r"(?<![^\s('\"])--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)", lambda m: m.group(1).replace("-", "_"), message)


def cli_json(*args):
    code, out, _ = cli(*args, "--json", check=False)
    assert code in (0, 1), out
    return json.loads(out)


@pytest.fixture(scope="session")
def tubes(tmp_path_factory):
    """A nominal tube (mesh) and a scan of it with ovality and noise (mesh), radius 50 mm, 3000 vertices."""
    d = tmp_path_factory.mktemp("tubes")
    nominal, scan = d / "nominal.ply", d / "scan.ply"
    cli("generate", "tube", "--out", nominal, "--radius", 50, "--length", 100, "--vertices", 2000, "--quiet")
    cli("generate", "tube", "--out", scan, "--radius", 50, "--length", 100, "--vertices", 3000, "--ovality", 0.4,
        "--noise", 0.02, "--seed", 3, "--quiet")
    transform = d / "T.txt"
    transform.write_text("0.99995 -0.01 0 0.1\n0.01 0.99995 0 -0.2\n0 0 1 0.05\n0 0 0 1\n")
    return {"dir": d, "nominal": nominal, "scan": scan, "transform": transform}
