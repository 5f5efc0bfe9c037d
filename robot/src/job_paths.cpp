#include "conform/robot/job_paths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/error.h"

namespace conform {
namespace {

Eigen::Vector3d row_vector(const CsvTable& t, std::size_t row, const char* a, const char* b, const char* c) {
  return {t.number(row, t.column(a)), t.number(row, t.column(b)), t.number(row, t.column(c))};
}

Eigen::Vector3d position(const CsvTable& t, std::size_t row) { return row_vector(t, row, "x_mm", "y_mm", "z_mm"); }

void check_axis(const CsvTable& t, std::size_t row, const Eigen::Vector3d& axis, const char* what) {
  const double norm = axis.norm();
  // The jobs write unit vectors with 6 to 9 decimals; anything far from unit length is not such a vector.
  if (!(std::abs(norm - 1.0) <= 1e-3)) {
    throw Error(t.path + ":" + std::to_string(t.line_numbers[row]) + ": the " + what +
                " is not a unit vector (length " + std::to_string(norm) + ")");
  }
}

struct Grouped {
  std::string name;
  ToolPathPoints points;
};

// Rows with the same key, in file order of first appearance; a key that comes back after another is refused.
class Grouper {
 public:
  explicit Grouper(const CsvTable& t) : table_(t) {}
  ToolPathPoints& at(const std::string& key, std::size_t row) {
    if (groups_.empty() || groups_.back().name != key) {
      if (seen_.count(key) > 0) {
        throw Error(table_.path + ":" + std::to_string(table_.line_numbers[row]) + ": '" + key +
                    "' comes back after other rows; a path's rows must be consecutive");
      }
      seen_[key] = groups_.size();
      groups_.push_back({key, {}});
    }
    return groups_.back().points;
  }
  std::vector<Grouped>& groups() { return groups_; }

 private:
  const CsvTable& table_;
  std::vector<Grouped> groups_;
  std::map<std::string, std::size_t> seen_;
};

void add(ToolPathPoints* p, const Eigen::Vector3d& position, const Eigen::Vector3d& axis) {
  p->positions.push_back(position);
  p->tool_axes.push_back(axis);
}

std::vector<Grouped> tube_joint(const CsvTable& t) {
  Grouped g{"seam", {}};
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const Eigen::Vector3d d = row_vector(t, r, "dx", "dy", "dz");
    check_axis(t, r, d, "direction (dx, dy, dz)");
    add(&g.points, position(t, r), d);  // Eq. 10-11: the tool stands at p - s d and points along d
  }
  g.points.closed = true;  // phi in [0, 2 pi): the seam closes on its first row
  return {g};
}

std::vector<Grouped> saddle(const CsvTable& t) {
  Grouped g{"seam", {}};
  const std::size_t theta = t.column("theta_rad");
  const std::size_t pose = t.column("pose_rad");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double th = t.number(r, theta);
    const double ps = t.number(r, pose);
    // The torch lies in the plane of the pipe axis z_P and the pipe's outward normal n_p = (sin th, cos th, 0)
    // (Xue et al. 2018, Fig. 2), at the pose angle from the pipe axis, pointing down into the seam (Eq. 12).
    const Eigen::Vector3d n_p(std::sin(th), std::cos(th), 0.0);
    add(&g.points, position(t, r), -std::cos(ps) * Eigen::Vector3d::UnitZ() - std::sin(ps) * n_p);
  }
  return {g};
}

std::vector<Grouped> sicp(const CsvTable& t) {
  Grouped g{"trajectory", {}};
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const Eigen::Vector3d n = row_vector(t, r, "nx", "ny", "nz");
    check_axis(t, r, n, "tool normal (nx, ny, nz)");
    add(&g.points, position(t, r), -n);
  }
  return {g};
}

std::vector<Grouped> profile(const CsvTable& t) {
  Grouper groups(t);
  const std::size_t id = t.column("id");
  const std::size_t index = t.column("i");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (t.integer(r, index) < 0) continue;  // a circle's or slot's centre: a reference, not cut
    const Eigen::Vector3d n = row_vector(t, r, "nx", "ny", "nz");
    check_axis(t, r, n, "web normal (nx, ny, nz)");
    ToolPathPoints& p = groups.at(t.text(r, id), r);
    add(&p, position(t, r), -n);
    p.hints.push_back(row_vector(t, r, "dx", "dy", "dz"));
  }
  return std::move(groups.groups());
}

std::vector<Grouped> weld_layers(const CsvTable& t) {
  Grouper groups(t);
  const std::size_t layer = t.column("layer");
  const std::size_t pass = t.column("path");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const Eigen::Vector3d n = row_vector(t, r, "nx", "ny", "nz");
    check_axis(t, r, n, "normal (nx, ny, nz)");
    const std::string key =
        "layer " + std::to_string(t.integer(r, layer)) + " path " + std::to_string(t.integer(r, pass));
    add(&groups.at(key, r), position(t, r), -n);
  }
  return std::move(groups.groups());
}

// Frames given as columns (conform export's csv format, or a job that writes qw,qx,qy,qz): taken as they are, one
// segment per `segment` value; approach and retract rows (`kind`) are left out, the program makes its own.
std::vector<ToolSegment> given_frames(const CsvTable& t) {
  std::vector<ToolSegment> segments;
  const bool has_segment = t.has_column("segment");
  const bool has_kind = t.has_column("kind");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    if (has_kind && t.text(r, t.column("kind")) != "path") continue;
    const std::string key = has_segment ? t.text(r, t.column("segment")) : "frames";
    if (segments.empty() || segments.back().name != key) {
      for (const ToolSegment& s : segments) {
        if (s.name == key) {
          throw Error(t.path + ":" + std::to_string(t.line_numbers[r]) + ": segment '" + key +
                      "' comes back after other rows; a path's rows must be consecutive");
        }
      }
      segments.push_back({key, {}});
    }
    const Eigen::Vector4d q(t.number(r, t.column("qw")), t.number(r, t.column("qx")), t.number(r, t.column("qy")),
                            t.number(r, t.column("qz")));
    if (!(std::abs(q.norm() - 1.0) <= 1e-3)) {
      throw Error(t.path + ":" + std::to_string(t.line_numbers[r]) + ": the quaternion (qw, qx, qy, qz) is not of " +
                  "unit length (" + std::to_string(q.norm()) + ")");
    }
    ToolFrame f;
    f.position = position(t, r);
    f.rotation = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized().toRotationMatrix();
    segments.back().frames.push_back(f);
  }
  return segments;
}

bool has_all(const CsvTable& t, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (!t.has_column(name)) return false;
  }
  return true;
}

}  // namespace

std::string detect_path_job(const CsvTable& t) {
  const bool xyz = has_all(t, {"x_mm", "y_mm", "z_mm"});
  const bool normal = has_all(t, {"nx", "ny", "nz"});
  if (xyz && has_all(t, {"qw", "qx", "qy", "qz"})) return "frames";
  if (xyz && normal && has_all(t, {"layer", "path", "i"})) return "weld-layers";
  if (xyz && normal && has_all(t, {"id", "i", "dx", "dy", "dz"})) return "profile";
  if (xyz && has_all(t, {"theta_rad", "pose_rad"})) return "saddle";
  if (xyz && has_all(t, {"phi_rad", "dx", "dy", "dz"})) return "tube-joint";
  if (xyz && has_all(t, {"nsx", "nlx"})) {
    throw Error(t.path +
                ": a tube-joint path file (seam and normals) has no tool; export the cut file (--out-cut) "
                "or the weld file (--out-weld) instead");
  }
  if (xyz && normal) return "sicp";
  throw Error(t.path +
              ": not a path file of a conform job: the header needs x_mm,y_mm,z_mm and the tool's direction: "
              "dx,dy,dz with phi_rad (tube-joint cut or weld), theta_rad,pose_rad (saddle), nx,ny,nz (sicp), "
              "with id,i,dx,dy,dz (profile) or with layer,path,i (weld-layers)");
}

namespace {

// A step no path's own spacing makes suspicious below this, mm (a few coarse points of a short seam).
constexpr double kMinJumpMm = 1.0;

// Every cell of every column that is not text (a feature's id, a frame file's segment and kind) is a number, used
// by the job's frames or not: a broken column is a broken file.
void check_numeric_columns(const CsvTable& t) {
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    const std::string& name = t.columns[c];
    if (name == "id" || name == "segment" || name == "kind") continue;
    for (std::size_t r = 0; r < t.rows(); ++r) t.number(r, c);
  }
}

// A step far beyond the segment's median step (and beyond 1 mm): a broken row, not a move.
void check_jumps(const CsvTable& t, const ToolPath& path, double max_ratio) {
  if (max_ratio <= 0.0) return;
  for (const ToolSegment& s : path.segments) {
    std::vector<double> steps;
    for (std::size_t i = 1; i < s.frames.size(); ++i) {
      steps.push_back((s.frames[i].position - s.frames[i - 1].position).norm());
    }
    if (steps.size() < 2) continue;
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double limit = std::max(kMinJumpMm, max_ratio * median);
    for (std::size_t i = 0; i < steps.size(); ++i) {
      if (steps[i] <= limit) continue;
      char text[320];
      std::snprintf(text, sizeof text,
                    ": segment '%s': a jump of %.6g mm between points %zu and %zu, %.0f times its median step of "
                    "%.6g mm: a broken row, not a move (export --max-jump-ratio 0 allows it)",
                    s.name.c_str(), steps[i], i + 1, i + 2, steps[i] / std::max(median, 1e-12), median);
      throw Error(t.path + text);
    }
  }
}

}  // namespace

ToolPath tool_path_from_csv(const CsvTable& table, const ToolFrameOptions& options, ToolFrameFigures* figures) {
  ToolPath path;
  path.job = detect_path_job(table);
  if (table.rows() == 0) throw Error(table.path + ": no rows (an empty path)");
  check_numeric_columns(table);
  std::vector<Grouped> groups;
  if (path.job == "tube-joint") groups = tube_joint(table);
  if (path.job == "saddle") groups = saddle(table);
  if (path.job == "sicp") groups = sicp(table);
  if (path.job == "profile") groups = profile(table);
  if (path.job == "weld-layers") groups = weld_layers(table);
  ToolFrameFigures local;
  ToolFrameFigures& fig = figures != nullptr ? *figures : local;
  if (path.job == "frames") path.segments = given_frames(table);
  for (Grouped& g : groups) {
    ToolSegment segment{g.name, build_tool_frames(g.points, options, &fig)};
    // A closed seam ends where it began.
    if (g.points.closed && !segment.frames.empty()) segment.frames.push_back(segment.frames.front());
    path.segments.push_back(std::move(segment));
  }
  if (path.segments.empty()) throw Error(table.path + ": no path rows (only centres, i = -1, or approach moves)");
  check_jumps(table, path, options.max_jump_ratio);
  measure_orientation_steps(path, &fig);
  return path;
}

}  // namespace conform
