"""conform for Python: the jobs of the `conform` CLI on paths, numpy arrays or what `conform.read` returns.

Every job runs the pipeline the CLI runs (same options, same defaults, same messages, same numbers) and returns a
`Result` whose fields are the keys of the CLI's `--json` output, plus per-point numpy arrays aligned with the input
(NaN where unmatched). Bad input raises `conform.Error` with the CLI's message, worded for the caller: a flag named as
the keyword argument it is (`cad_deflection`, not `--cad-deflection`), geometry given in memory as its argument, not
as a temporary file. See docs/python.md.

Output files are checked as the CLI checks them, before any work: an output that is one of the call's inputs (also
through a symbolic or a hard link) or that is given twice raises `conform.Error`; the files of one call are written
all or none. Face indices must be integers in [0, vertex count) (integral floats too), or the call raises ValueError.

The jobs with the CLI's `--report` (align, compare, fit_cylinder, saddle, weld_layers, profile, tube_joint, sicp) take
`report="page.html"`: the same self-contained HTML page, byte for byte (docs/report.md).
"""

import json as _json

import numpy as _np

from . import _conform
from ._conform import Error, Geometry, read

__all__ = ["Error", "Geometry", "Result", "read", "align", "compare", "inspect", "pose_error", "fit_cylinder", "saddle", "generate_tube", "weld_layers", "profile", "tube_joint", "sicp", "export", "generate_eroded", "generate_profile", "generate_plate", "generate_nosecone", "generate_tube_joint", "JOBS"]


class Result:
    """A job's answer: one attribute per key of the CLI's JSON, plus the job's arrays.

    Transforms (4x4 lists in the JSON, e.g. T_ref_scan) are (4, 4) numpy arrays here; `to_dict()` gives the JSON's
    own values. `arrays` names the per-point numpy arrays (e.g. deviation_mm); `warnings` what the job warned about
    (the CLI prints them on stderr).
    """

    def __init__(self, job, values, arrays):
        self.job = job
        self._values = values
        self.warnings = list(arrays.pop("warnings", []))
        self.arrays = tuple(arrays)
        for key, value in values.items():
            if key.startswith("T_") and value is not None:
                value = _np.asarray(value, dtype=float)
            setattr(self, key, value)
        for key, value in arrays.items():
            setattr(self, key, value)

    def to_dict(self):
        """The CLI's JSON for the same inputs, as a dict (a deep copy)."""
        return _json.loads(_json.dumps(self._values))

    def __repr__(self):
        shown = ", ".join(f"{k}={self._values[k]!r}" for k in list(self._values)[:6])
        return f"<conform.Result {self.job}: {shown}, ...>"


def _result(job, answer):
    text, arrays, in_memory = answer
    values = _json.loads(text)
    for key in in_memory:  # a temporary file named by the JSON: the input was given in memory
        values[key] = None
    return Result(job, values, dict(arrays))


def align(scan, reference, **options):
    """`conform align`: T_ref_scan of a scan against its reference, convergence, fit figures, the pose's predicted
    standard deviations, the motions the scan does not constrain and whether to trust the pose (`trust`).

    scan, reference: path, (N, 3) array, (vertices, faces) pair or conform.Geometry. Options as the CLI's flags:
    method ("" automatic, point-to-point, point-to-plane, point-to-surface, plane-to-plane), init (none, pca, fpfh,
    pairs:FILE), max_distance, overlap, max_iterations, free_tolerance_mm, free_tolerance_deg, pose_tolerance_mm,
    tolerance, max_noise_ratio, units (both inputs), scan_units, reference_units (one input each, over units),
    out_transform, out_aligned, report, progress. Not converged or not trusted (CLI exit 1): `converged` is False.
    """
    return _result("align", _conform.align(scan, reference, **options))


def compare(scan, reference, **options):
    """`conform compare`: signed deviation of each scan point from the reference surface (mm), statistics.

    scan, reference: path, (N, 3) array, (vertices, faces) pair or conform.Geometry. Options: transform (path or
    (4, 4) T_ref_scan; its translation in the reference's units), tolerance, out_deviation, out_histogram, units (both
    inputs), scan_units, reference_units (one input each, over units), report, progress (callable(stage, fraction)).
    Arrays: deviation_mm (N,), closest_mm (N, 3), NaN where unmatched.
    """
    return _result("compare", _conform.compare(scan, reference, **options))


def inspect(scan, reference, **options):
    """`conform inspect`: the scan inspected by the CAD's faces: per face (the JSON's `faces`) the signed deviation,
    the form and the fitted feature against its nominal (docs/inspect.md).

    scan: path, (N, 3) array, (vertices, faces) pair or conform.Geometry; reference: the CAD's path (.step .stp .iges
    .igs). Options as the CLI's flags: transform (path or (4, 4) T_ref_scan), align ("best-fit"), datums (face ids,
    primary first), max_distance, max_normal_angle_deg, form_trim, min_fit_points, tolerances (path), out_faces,
    units, cad_deflection, cad_angle_deg, cad_save_mesh, report, progress. Arrays: point_face (N,), each point's face id, 0
    for none.
    """
    return _result("inspect", _conform.inspect(scan, reference, **options))


def pose_error(transform_a, transform_b, **options):
    """`conform pose-error`: rotation (deg) and translation (mm) between two transforms (paths or (4, 4) arrays)."""
    return _result("pose_error", _conform.pose_error(transform_a, transform_b, **options))


def fit_cylinder(input, **options):
    """`conform fit-cylinder`: axis, radius, inliers of a tube scan. Options as the CLI's flags: threshold,
    min_radius, max_radius, axis, axis_tolerance_deg, normals_k, seed, max_shape_ambiguity, points (auto, vertices, surface),
    surface_samples, out, report, progress. Arrays: inlier (N,) bool."""
    return _result("fit_cylinder", _conform.fit_cylinder(input, **options))


def saddle(**options):
    """`conform saddle`: the saddle weld path. Arrays: theta_rad, position_mm (N, 3), pose_rad, step_mm."""
    return _result("saddle", _conform.saddle(**options))


def weld_layers(eroded, **options):
    """`conform weld-layers`: crater rims and weld paths layer by layer. Arrays (the CSV's rows): layer, path,
    points_mm (M, 3), normals (M, 3)."""
    return _result("weld_layers", _conform.weld_layers(eroded, **options))


def profile(edge, features, **options):
    """`conform profile`: where to cut a deformed ship profile's features. Arrays (the CSV's rows): feature (index
    into `features`), points_mm (M, 3), normals (M, 3), directions (M, 3)."""
    return _result("profile", _conform.profile(edge, features, **options))


def tube_joint(leg, stub, **options):
    """`conform tube-joint`: cutting and welding paths of a stub on a leg, from their scans (paths, arrays or
    Geometry). Options, named like the CLI's flags, defaults as the CLI's: pitch_deg, offset, protrusion (or
    leg_pose: path or (4, 4) T_S_L), leg_markers, stub_markers, marker_tolerance, backtrack_tolerance,
    max_facet_error, island_ratio, wall_thickness (mm, or [leg, stub]), step_deg or step_mm, smoothing,
    smoothing_rms, groove_deg ([toe, side, heel, side]), groove_table, groove_interpolation, weld_angle_deg,
    cut_standoff, weld_standoff, k_normals, k_refine, out_path, out_cut, out_weld, report, progress.
    Arrays (the path's rows): phi_rad, points_mm, tangents, stub_normals, leg_normals, cut_directions,
    weld_directions (M, 3), groove_rad, psi_rad."""
    return _result("tube_joint", _conform.tube_joint(leg, stub, **options))


def sicp(contour, scan, trajectory, **options):
    """`conform sicp`: a nominal deburring trajectory mapped onto the scanned, deformed part (Subdivision-ICP, one
    rigid transform or the projection model). contour: path (CSV polyline or a mesh whose boundary is taken); scan:
    path, (N, 3) array, (vertices, faces) pair or conform.Geometry; trajectory: path (CSV x,y,z,nx,ny,nz). Options as
    the CLI's flags: surface, segment_length, overlap, curvature_radius, model, projection_fit, neighbourhood,
    stability, max_distance, coarse_max_distance, scan_voxel, no_joint, joint_weight, joint_damping, max_iterations,
    min_edge_points, edge_radius, max_edge_gap, outlier_ratio, max_offset, normal_smoothing, normals, truth,
    out_trajectory, out_rows, report, progress. Arrays: points_mm, normals (M, 3): the compensated trajectory, empty when it
    cannot be trusted (`trusted` False, the CLI's exit 1)."""
    return _result("sicp", _conform.sicp(contour, scan, trajectory, **options))


def export(path, **options):
    """`conform export`: a job's path CSV (tube-joint cut or weld, saddle, sicp trajectory, profile, weld-layers) as a
    robot or CNC program; a list of them goes into one program in order (the CLI's repeated --path). Options as the CLI's flags: format (krl, rapid, urscript, fanuc, val3, gcode, csv) and out
    (required), frame (path or (4, 4) T_base_part), speed_mm_s, approach_speed_mm_s, approach_mm, name, tool,
    work_object, max_points, three_axis, roll_cone_deg, preferred_x ([x, y, z]). `written` lists the files."""
    return _result("export", _conform.export(path, **options))


def generate_tube(out, **options):
    """`conform generate tube`: a synthetic tube scan written to `out` (.ply/.stl) with its truth beside it. Options
    as the CLI's flags: radius, length, arc_deg, arc_center_deg, inner, edge or vertices, axis_point, axis_direction,
    azimuth_reference, ovality, ovality_azimuth_deg, seam_height, seam_width, seam_azimuth_deg, bump (a list of
    [az_deg, z_mm, height_mm, radius_mm]), bow, bow_azimuth_deg, noise, noise_type, noise_direction, hole (a list of
    [az_deg, z_mm, radius_mm]), holes, hole_radius, outliers, outlier_distance, seed, ascii, double, normals,
    progress. Read the scan back with conform.read(out)."""
    return _result("generate_tube", _conform.generate_tube(out, **options))


def generate_eroded(out, **options):
    """`conform generate eroded`: a synthetic eroded blade grid written to `out` (.csv), with the reference grid and
    the true crater rims beside it. Options as the CLI's flags: rows, cols, length, width, chord_radius, span_radius,
    twist, crater (a list of [x_mm, y_mm, radius_mm, depth_mm (, inner_radius_mm (, lip_mm, lip_width_mm))]; None:
    the CLI's one default crater), bump (a list of [x_mm, y_mm, radius_mm, height_mm]), reference_offset,
    reference_tilt_deg, noise, seed."""
    return _result("generate_eroded", _conform.generate_eroded(out, **options))


def generate_profile(out, **options):
    """`conform generate profile`: a deformed ship profile's measured edge written to `out` (.csv), with the
    designed features and the ground truth beside it. Options as the CLI's flags: length, width, bow, bow_asymmetry,
    bow_out, twist_deg, kink_deg, kink_at, kink_length, spacing, noise, dropouts, second_edge, holes, hole_radius,
    hole_tx, marking_line, outliers, outlier_mm, offset ([x, y, z]), reverse, seed."""
    return _result("generate_profile", _conform.generate_profile(out, **options))


_PANEL = """Common options as the CLI's flags: band, thickness, surface_edge, contour_spacing, trajectory_spacing,
    scan_points (0: the shape's default), noise, missing, missing_patches, missing_depth, holes, hole_radius, field,
    field_wavelength, seed, progress."""


def generate_plate(out, **options):
    """`conform generate plate`: a deformed double-curvature plate with a porthole, its scan written to `out` (.ply)
    and beside it the nominal surface, contour, trajectory and the true (deformed) trajectory, sicp's inputs. Plate
    options: radius_x, radius_y, porthole_width, porthole_height, round, clamp_span, sag, bend, twist, opening
    (ellipse or rectangle), corner_radius. """
    return _result("generate_plate", _conform.generate_plate(out, **options))


def generate_nosecone(out, **options):
    """`conform generate nosecone`: as generate_plate, a barrel section with a cockpit-like opening. Its options:
    radius, window_height, window_bottom, window_top, corner_radius, ovality, droop. """
    return _result("generate_nosecone", _conform.generate_nosecone(out, **options))


generate_plate.__doc__ += _PANEL
generate_nosecone.__doc__ += _PANEL


def generate_tube_joint(out_leg, out_stub, out_truth, **options):
    """`conform generate tube-joint`: a posed leg + stub scan pair (meshes) and the true intersection curve (CSV),
    tube_joint's input. Options as the CLI's flags: pitch_deg, offset, protrusion (0: automatic), leg_radius,
    stub_radius, wall, edge, leg_vertices, stub_vertices, ovality_pct, peaking, leg_seam_deg, stub_seam_deg,
    seam_width, leg_bump and stub_bump (lists of [az_deg, z_mm, height_mm, radius_mm]), noise, leg_arc_deg,
    stub_length, truth_points, seed, ascii."""
    return _result("generate_tube_joint", _conform.generate_tube_joint(out_leg, out_stub, out_truth, **options))


# The jobs conform.batch can run, by the manifest's `job` column.
JOBS = {"align": align, "compare": compare, "inspect": inspect, "pose_error": pose_error, "fit_cylinder": fit_cylinder, "saddle": saddle, "weld_layers": weld_layers, "profile": profile, "tube_joint": tube_joint, "sicp": sicp, "export": export}
