#include "conform/pipelines/sicp/sicp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/mesh_boundary.h"
#include "conform/core/nearest_neighbors.h"
#include "common/cad_inputs.h"

namespace conform {
namespace {

const std::vector<std::string> kTrajectoryColumns = {"x_mm", "y_mm", "z_mm", "nx", "ny", "nz"};

bool is_csv(const std::string& path) { return file_extension(path) == ".csv"; }

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// An ordered point list is closed when its last point is back near its first (a repeated first point is dropped):
// the closing gap is no longer than three median spacings, or, on an unevenly spaced contour (a CAD export with long
// steps on straight sides and short ones in the bends), no longer than 1.5 times its longest step while the closing
// edge continues both ends without a turn of more than 45 deg, or the trajectory closes on itself (its first and last
// rows within three of its median row spacings) and the gap is at most a tenth of the contour. (Three median
// spacings alone read a triangle with 20 mm steps on its sides and a 16.5 mm closing gap as open: its rows slid.)
bool closes(const Polyline& c, const Trajectory& trajectory) {
  std::vector<double> spacing;
  for (std::size_t i = 1; i < c.points.size(); ++i) spacing.push_back((c.points[i] - c.points[i - 1]).norm());
  const double longest = *std::max_element(spacing.begin(), spacing.end());
  const double median = median_of(spacing);
  const Eigen::Vector3d closing = c.points.front() - c.points.back();
  const double gap = closing.norm();
  if (gap <= 3.0 * median) return true;
  const Eigen::Vector3d last = c.points.back() - c.points[c.points.size() - 2];
  const Eigen::Vector3d first = c.points[1] - c.points.front();
  const double cos45 = std::sqrt(0.5);
  if (gap <= 1.5 * longest && closing.dot(last) >= cos45 * gap * last.norm() &&
      closing.dot(first) >= cos45 * gap * first.norm())
    return true;
  std::vector<double> rows;
  for (std::size_t i = 1; i < trajectory.points.size(); ++i)
    rows.push_back((trajectory.points[i] - trajectory.points[i - 1]).norm());
  const bool trajectory_closed = trajectory.points.size() >= 3 &&
                                 (trajectory.points.back() - trajectory.points.front()).norm() <= 3.0 * median_of(rows);
  return trajectory_closed && gap <= 0.1 * (std::accumulate(spacing.begin(), spacing.end(), 0.0) + gap);
}

Polyline contour_from_csv(const std::string& path, const Trajectory& trajectory) {
  const CsvTable table = read_csv(path, {"x_mm", "y_mm", "z_mm"});
  if (table.rows() < 3)
    throw Error(path + ": a contour needs at least 3 points, the file has " + std::to_string(table.rows()));
  const Eigen::MatrixXd xyz = table.numbers({"x_mm", "y_mm", "z_mm"});
  Polyline c;
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) c.points.emplace_back(xyz(i, 0), xyz(i, 1), xyz(i, 2));
  std::vector<double> spacing;
  for (std::size_t i = 1; i < c.points.size(); ++i) spacing.push_back((c.points[i] - c.points[i - 1]).norm());
  const double gap = (c.points.back() - c.points.front()).norm();
  if (gap <= 1e-9 * std::max(1.0, median_of(spacing))) c.points.pop_back();
  if (c.points.size() < 3)
    throw Error(path + ": a contour needs at least 3 distinct points, the file has " + std::to_string(c.points.size()));
  c.closed = closes(c, trajectory);
  return c;
}

// The boundary loop the trajectory follows: the smallest median distance from the trajectory's rows to the loop (a
// loop on the scan is not enough: the flank's bottom edge and the band's outer rim may both be scanned).
Polyline contour_from_mesh(const Mesh& mesh, const std::string& path, const Trajectory& trajectory,
                           std::string* source) {
  const std::vector<Polyline> loops = boundary_polylines(mesh);
  if (loops.empty())
    throw Error(path + ": the mesh has no boundary (no edge used by one triangle only) to take as the contour");
  std::size_t best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  const std::size_t step = std::max<std::size_t>(1, trajectory.points.size() / 200);
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const KdTree loop_tree(loops[k].points);
    std::vector<float> d;
    for (std::size_t i = 0; i < trajectory.points.size(); i += step) {
      float sq = 0.0f;
      loop_tree.nearest(trajectory.points[i].cast<float>(), &sq);
      d.push_back(sq);
    }
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    if (d[d.size() / 2] < best_distance) best_distance = d[d.size() / 2], best = k;
  }
  *source = "mesh boundary " + std::to_string(best + 1) + " of " + std::to_string(loops.size());
  return loops[best];
}

Trajectory read_trajectory(const std::string& path) {
  const CsvTable table = read_csv(path, kTrajectoryColumns);
  if (table.rows() == 0) throw Error(path + ": the trajectory has no rows");
  const Eigen::MatrixXd m = table.numbers(kTrajectoryColumns);
  Trajectory t;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    const Eigen::Vector3d n(m(i, 3), m(i, 4), m(i, 5));
    if (std::abs(n.norm() - 1.0) > 1e-3) {
      throw Error(path + ":" + std::to_string(table.line_numbers[static_cast<std::size_t>(i)]) +
                  ": the tool normal (nx, ny, nz) is not of unit length (" + std::to_string(n.norm()) + ")");
    }
    t.points.emplace_back(m(i, 0), m(i, 1), m(i, 2));
    t.normals.push_back(n.normalized());
  }
  return t;
}

void write_rows(const std::string& path, const SicpCheck& c) {
  CsvWriter writer(
      {"row", "across_mm", "axis_mm", "along_mm", "confidence", "contour_distance_mm", "edge_points", "gap_mm"}, 6);
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const SicpRowReport& r = c.rows[i];
    writer.cell(static_cast<std::int64_t>(i + 1));
    for (double v : {r.across_mm, r.axis_mm, r.along_mm, r.confidence, r.contour_distance_mm}) writer.cell(v);
    writer.cell(static_cast<std::int64_t>(r.edge_points));
    writer.cell(r.gap_mm);
    writer.end_row();
  }
  writer.write(path);
}

void write_trajectory(const std::string& path, const Trajectory& t) {
  CsvWriter writer(kTrajectoryColumns, 6);
  for (std::size_t i = 0; i < t.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) writer.cell(t.points[i](k));
    for (int k = 0; k < 3; ++k) writer.cell(t.normals[i](k));
    writer.end_row();
  }
  writer.write(path);
}

std::vector<Eigen::Vector3d> points_of(const Cloud& cloud) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

}  // namespace

bool SicpJobOptions::IsValid(std::string* error) const {
  std::string why;
  if (contour_path.empty())
    why = "no contour: give --contour (CSV x_mm,y_mm,z_mm or a mesh)";
  else if (scan_path.empty())
    why = "no scan: give --scan";
  else if (trajectory_path.empty())
    why = "no trajectory: give --trajectory (CSV x_mm,y_mm,z_mm,nx,ny,nz)";
  else if (is_csv(contour_path) && surface_path.empty())
    why =
        "a CSV contour needs --surface (the nominal surface mesh around it): contour-only S-ICP pairs the contour "
        "with the scanned surface beside the edge, not with the edge, and is refused; or give the nominal mesh as "
        "--contour";
  else if (!out_trajectory_path.empty() && !is_csv(out_trajectory_path))
    why = out_trajectory_path + ": the compensated trajectory is written as .csv";
  else if (!out_rows_path.empty() && !is_csv(out_rows_path))
    why = out_rows_path + ": the per-row report is written as .csv";
  else if (!compensation.checks.IsValid(&why))
    why = "checks: " + why;
  else if (!compensation.sicp.IsValid(&why))
    why = "S-ICP: " + why;
  else if (!compensation.projection.IsValid(&why))
    why = "projection: " + why;
  else if (!compensation.normals.IsValid(&why))
    why = "tool normals: " + why;
  else if (!compensation.misfit.IsValid(&why))
    why = "surface misfit: " + why;
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

SicpJobResult run_sicp(const SicpJobOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  SicpJobResult result;
  report(options.progress, "read", 0.0);
  ReadOptions read;
  read.non_finite = NonFinitePolicy::kDrop;
  ReadReport scan_report;
  const std::vector<Eigen::Vector3d> scan = points_of(read_cloud(options.scan_path, read, &scan_report));
  for (const std::string& w : scan_report.warnings) result.warnings.push_back(w);
  if (scan.empty()) throw Error(options.scan_path + ": the scan has no points");
  result.scan_points = scan.size();
  const Trajectory nominal = read_trajectory(options.trajectory_path);
  result.trajectory_rows = nominal.points.size();
  Mesh surface;
  bool has_surface = false;
  if (!options.surface_path.empty()) {
    ReadReport surface_report;
    surface = read_geometry(options.surface_path, detail::read_options(read.non_finite, options.cad), &surface_report);
    for (const std::string& w : surface_report.warnings) result.warnings.push_back(w);
    detail::keep_cad_report(surface_report, result.cad_inputs);
    has_surface = true;
  }
  Polyline contour;
  if (is_csv(options.contour_path)) {
    contour = contour_from_csv(options.contour_path, nominal);
    result.contour_source = "csv";
  } else {
    const Mesh mesh = read_mesh(options.contour_path, read);
    contour = contour_from_mesh(mesh, options.contour_path, nominal, &result.contour_source);
    if (!has_surface) surface = mesh, has_surface = true;
  }
  result.contour_source += contour.closed ? " (closed)" : " (open)";
  result.contour_points = contour.points.size();
  result.contour_length_mm = length(contour);
  result.surface_faces = surface.faces.size();
  std::optional<Trajectory> truth;
  if (!options.truth_path.empty()) {
    truth = read_trajectory(options.truth_path);
    if (truth->points.size() != nominal.points.size()) {
      throw Error(options.truth_path + ": " + std::to_string(truth->points.size()) + " rows, the trajectory has " +
                  std::to_string(nominal.points.size()));
    }
  }
  report(options.progress, "read", 1.0);

  SicpCompensationOptions compensation = options.compensation;
  compensation.sicp.progress = options.progress;
  result.compensation = compensate_trajectory(contour, has_surface ? &surface : nullptr, scan, nominal, compensation);
  for (const std::string& w : result.compensation.registration.warnings) result.warnings.push_back(w);
  for (const std::string& w : result.compensation.check.warnings) result.warnings.push_back(w);
  if (truth) result.error = trajectory_error(result.compensation.trajectory, *truth, nominal);
  if (options.keep_geometry) {
    result.contour = contour;
    result.scan = scan;
    result.nominal = nominal;
  }
  if (result.compensation.trusted) {
    report(options.progress, "write", 0.0);
    if (!options.out_trajectory_path.empty()) {
      write_trajectory(options.out_trajectory_path, result.compensation.trajectory);
      result.out_trajectory_path = options.out_trajectory_path;
    }
    if (!options.out_rows_path.empty()) {
      write_rows(options.out_rows_path, result.compensation.check);
      result.out_rows_path = options.out_rows_path;
    }
    report(options.progress, "write", 1.0);
  }
  return result;
}

}  // namespace conform
