"""The CLI's output checks in every Python job (issue 32): an output that is an input (also through a symbolic or a
hard link) raises before any work and leaves the input as it was; the outputs of a call are written all or none.
Face indices from numpy are integers in range, or the call raises naming the argument and the value."""

import os

import numpy as np
import pytest

import conform

IDENTITY = "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n"


def _file(path, text="the only copy\n"):
    path.write_text(text)
    return path


def _aliases(tmp_path, target):
    """The target itself, a symbolic link to it and a hard link to it."""
    link = tmp_path / f"link_{target.name}"
    link.symlink_to(target)
    hard = tmp_path / f"hard_{target.name}"
    os.link(target, hard)
    return [target, link, hard]


# Each job with an input its output names: the refusal comes before the input is read, so any content will do.
CASES = {
    "compare": lambda f, out: conform.compare(f, f.with_name("ref.ply"), out_deviation=out),
    "compare_histogram": lambda f, out: conform.compare(f.with_name("scan.ply"), f, out_histogram=out),
    "profile": lambda f, out: conform.profile(f, f.with_name("features.csv"), out=out),
    "sicp": lambda f, out: conform.sicp(f.with_name("contour.csv"), f.with_name("scan.ply"), f, out_trajectory=out),
    "weld_layers": lambda f, out: conform.weld_layers(f, reference_from_border=True, bead_spacing=1,
                                                      layer_height=1, chord_error=0.1, out=out),
    "export": lambda f, out: conform.export(f, format="krl", out=out),
    "export_frame": lambda f, out: conform.export(f.with_name("path.csv"), format="krl", frame=f, out=out),
    "fit_cylinder": lambda f, out: conform.fit_cylinder(f, out=out),
    "tube_joint": lambda f, out: conform.tube_joint(f, f.with_name("stub.ply"), pitch_deg=90, offset=0, protrusion=10,
                                                    out_path=out),
    "tube_joint_pose": lambda f, out: conform.tube_joint(f.with_name("leg.ply"), f.with_name("stub.ply"), leg_pose=f,
                                                         out_cut=out),
    "align": lambda f, out: conform.align(f, f.with_name("ref.ply"), out_aligned=out),
}


@pytest.mark.parametrize("job", sorted(CASES))
def test_an_output_that_is_an_input_raises_and_leaves_it(tmp_path, job):
    target = _file(tmp_path / "input.dat", IDENTITY)
    for alias in _aliases(tmp_path, target):
        with pytest.raises(conform.Error, match="this output is the input"):
            CASES[job](target, alias)
        assert target.read_text() == IDENTITY, (job, alias)
        assert sorted(p.name for p in tmp_path.iterdir() if "conform" in p.name) == []  # no temporary left


def test_an_output_given_twice_raises(tmp_path):
    with pytest.raises(conform.Error, match="given as two outputs"):
        conform.compare(tmp_path / "s.ply", tmp_path / "r.ply", out_deviation=tmp_path / "x.ply",
                        out_histogram=tmp_path / "x.ply")
    with pytest.raises(conform.Error, match="given as two outputs"):
        conform.generate_tube_joint(tmp_path / "a.ply", tmp_path / "a.ply", tmp_path / "t.csv")


def test_export_part_file_naming_an_input_writes_nothing(tmp_path):
    path = tmp_path / "seam.csv"
    conform.saddle(R=100, r=40, right_angle_pose_deg=45, step_deg=5, out=path)
    # 73 points, 20 a file: prog.src and parts prog_1.src ... prog_4.src; the frame is the file prog_2.src.
    frame = _file(tmp_path / "prog_2.src", IDENTITY)
    before = sorted(p.name for p in tmp_path.iterdir())
    with pytest.raises(conform.Error, match="prog_2.src: this output is the input"):
        conform.export(path, format="krl", out=tmp_path / "prog.src", frame=frame, max_points=20)
    assert frame.read_text() == IDENTITY
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nor prog.src nor any other part: all or none
    r = conform.export(path, format="krl", out=tmp_path / "prog.src", frame=np.eye(4), max_points=20)
    assert [os.path.basename(w) for w in r.written] == ["prog.src"] + [f"prog_{i}.src" for i in range(1, 5)]


def test_all_or_none_when_one_output_cannot_be_written(tmp_path):
    """A generator's three files: the truth's folder missing, neither mesh is written (refused before any work)."""
    with pytest.raises(conform.Error, match="does not exist"):
        conform.generate_tube_joint(tmp_path / "leg.ply", tmp_path / "stub.ply", tmp_path / "no" / "truth.csv")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(conform.Error, match="does not exist"):
        conform.saddle(R=100, r=40, right_angle_pose_deg=45, step_deg=5, out=tmp_path / "s.csv",
                       report=tmp_path / "no" / "page.html")
    assert list(tmp_path.iterdir()) == []


@pytest.fixture(scope="module")
def mesh(tubes):
    g = conform.read(tubes["nominal"])
    return np.array(g.points), np.array(g.faces)


def test_float_faces_with_integral_values_are_the_int_faces(tubes, mesh):
    points, faces = mesh
    by_int = conform.compare(tubes["scan"], (points, faces.astype(np.int64))).to_dict()
    by_float = conform.compare(tubes["scan"], (points, faces.astype(np.float64))).to_dict()
    by_list = conform.compare(tubes["scan"], (points, faces.tolist())).to_dict()
    assert by_float["rms_mm"] == by_int["rms_mm"] and by_list["rms_mm"] == by_int["rms_mm"]
    assert by_int["reference_faces"] == len(faces)


@pytest.mark.parametrize("bad, shown", [
    (1.5, "1.5: not an integer index"),
    (float("nan"), "nan: not an integer index"),
    (-1, "-1: a negative vertex index"),
    ("count", "not below the vertex count"),
    (2**31, "2147483648: above the largest index"),
    (2**32, "4294967296: above the largest index"),  # wrapped to vertex 0 before
    (2**32 + 5, "4294967301: above the largest index"),
])
def test_bad_face_indices_raise_naming_the_argument_and_value(tubes, mesh, bad, shown):
    points, faces = mesh
    dtype = np.float64 if isinstance(bad, float) else np.int64
    faces = faces.astype(dtype)
    faces[7, 2] = len(points) if bad == "count" else bad
    if bad == "count":
        shown = f"{len(points)}: not below the vertex count {len(points)}"
    with pytest.raises(ValueError, match=r"reference faces\[7, 2\] = " + shown.replace(".", r"\.")):
        conform.compare(tubes["scan"], (points, faces))
    if bad == 2**32 + 5:  # unsigned too
        with pytest.raises(ValueError, match="above the largest index"):
            conform.compare(tubes["scan"], (points, faces.astype(np.uint64)))


def test_non_integer_face_arrays_raise(tubes, mesh):
    points, faces = mesh
    with pytest.raises(ValueError, match="reference: faces must be an \\(F, 3\\) integer array"):
        conform.compare(tubes["scan"], (points, faces.astype(bool)))
    with pytest.raises(ValueError, match="reference: faces must be an \\(F, 3\\) integer array, got shape"):
        conform.compare(tubes["scan"], (points, faces[:, :2]))
