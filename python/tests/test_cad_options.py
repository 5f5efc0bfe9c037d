"""The CAD keyword arguments of the jobs that read geometry (the CLI's --cad-* and --flat-facets flags), and errors
named as the Python caller wrote the call: keyword arguments, not CLI flags; in-memory arguments, not temporary files."""

import pathlib

import numpy as np
import pytest

import conform
from conftest import cli_json
from test_jobs import assert_same

STEP = pathlib.Path(__file__).resolve().parents[2] / "tests" / "fuzz" / "corpus" / "cad" / "sphere.step"


@pytest.fixture(scope="module")
def sphere_scan(tmp_path_factory):
    """Points 0.01 mm outside the STEP sphere's tessellation, as a file."""
    sphere = conform.read(STEP, cad_deflection=0.05)
    centre = sphere.points.mean(axis=0)
    radial = sphere.points - centre
    points = centre + radial * (1.0 + 0.01 / np.linalg.norm(radial, axis=1))[:, None]
    path = tmp_path_factory.mktemp("sphere") / "scan.xyz"
    np.savetxt(path, points)
    return path


@pytest.mark.parametrize("flat", [False, True])
def test_compare_takes_the_cad_options_as_the_cli_does(tmp_path, sphere_scan, flat):
    flags = ["--flat-facets"] if flat else []
    expected = cli_json("compare", "--scan", sphere_scan, "--reference", STEP, "--cad-deflection", 0.05,
                        "--cad-angle-deg", 20, "--cad-save-mesh", tmp_path / "cli.ply", *flags)
    r = conform.compare(sphere_scan, STEP, cad_deflection=0.05, cad_angle_deg=20, cad_save_mesh=tmp_path / "py.ply",
                        flat_facets=flat)
    got = r.to_dict()
    # Every figure but the CAD report's, which names the mesh file written (another path for each).
    assert_same({k: v for k, v in got.items() if k != "cad"}, {k: v for k, v in expected.items() if k != "cad"})
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()


def test_the_deflection_changes_the_tessellation(tmp_path, sphere_scan):
    conform.compare(sphere_scan, STEP, cad_deflection=0.5, cad_save_mesh=tmp_path / "coarse.ply")
    conform.compare(sphere_scan, STEP, cad_deflection=0.05, cad_save_mesh=tmp_path / "fine.ply")
    assert len(conform.read(tmp_path / "fine.ply")) > 2 * len(conform.read(tmp_path / "coarse.ply"))
    assert len(conform.read(STEP, cad_deflection=0.05)) == len(conform.read(tmp_path / "fine.ply"))


def test_align_and_fit_cylinder_take_the_cad_options(tmp_path, sphere_scan):
    conform.align(sphere_scan, STEP, cad_deflection=0.05, cad_save_mesh=tmp_path / "align.ply")
    assert (tmp_path / "align.ply").exists()
    # A sphere is not a cylinder: the job runs (and says so); the mesh it measured is written all the same.
    conform.fit_cylinder(STEP, cad_deflection=0.05, cad_save_mesh=tmp_path / "fit.ply")
    assert (tmp_path / "fit.ply").exists()


def test_bad_cad_options_name_the_keyword_argument(sphere_scan):
    for kwargs, name in [({"cad_deflection": -1.0}, "cad_deflection"), ({"cad_angle_deg": 120}, "cad_angle_deg")]:
        with pytest.raises(conform.Error, match=name) as caught:
            conform.compare(sphere_scan, STEP, **kwargs)
        assert "--" not in str(caught.value)


def test_errors_name_keyword_arguments_not_cli_flags(tubes):
    # The message comes from code the CLI shares; its flag (--method) reads as the keyword argument.
    with pytest.raises(conform.Error) as caught:
        conform.align(tubes["scan"], tubes["nominal"], method="point-to-nowhere")
    assert "method" in str(caught.value) and "--method" not in str(caught.value)


def test_errors_name_in_memory_arguments_not_temporary_files(tubes):
    with pytest.raises(conform.Error) as caught:
        conform.compare(np.full((5, 3), np.nan), tubes["nominal"])
    message = str(caught.value)
    assert "the scan argument (given in memory)" in message and "conform-py-" not in message, message


def test_sicp_and_tube_joint_take_the_cad_options(tmp_path):
    # Checked before any file is read: a bad value names the keyword argument whatever the inputs.
    with pytest.raises(conform.Error, match="cad_deflection"):
        conform.sicp(tmp_path / "c.csv", tmp_path / "s.ply", tmp_path / "t.csv", cad_deflection=0)
    with pytest.raises(conform.Error, match="cad_angle_deg"):
        conform.tube_joint(tmp_path / "leg.ply", tmp_path / "stub.ply", pitch_deg=45, offset=0, protrusion=100,
                           cad_angle_deg=0)
