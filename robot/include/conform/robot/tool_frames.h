#pragma once
// Full tool frames along a path (docs/export.md): z = the tool axis, from the tool towards the work; x = the travel
// direction, the path's tangent projected off z; y = z x x. One place for every path job: the jobs give points and
// a tool axis (robot/job_paths.h), this builds the rest.
//
// Degenerate cases: a repeated point takes the tangent between its distinct neighbours; a tangent parallel to z (or a
// one-point segment) keeps the x of the nearest frame with a usable tangent (previous first, then next), else the
// point's hint tangent, else the base axis least aligned with z. Every frame is right-handed and orthonormal.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct ToolFrame {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      // tool centre point, mm
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns x (travel), y, z (tool axis) in the path's frame
};

// One continuous tool move (a seam, a feature's outline, a weld pass): the tool approaches before its first frame
// and retracts after its last.
struct ToolSegment {
  std::string name;  // e.g. "layer 1 path 2", "H1"
  std::vector<ToolFrame> frames;
};

struct ToolPath {
  std::string job;  // which job's file it came from ("saddle", "sicp", ...)
  std::vector<ToolSegment> segments;
  std::size_t frames() const;
};

// What a job's file gives per point; the tool axis any length > 0 (normalised here).
struct ToolPathPoints {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector3d> tool_axes;  // z: from the tool towards the work
  std::vector<Eigen::Vector3d> hints;      // optional (empty or one per point): travel where the points give none
  // The last point is followed by the first (the tangent wraps round); also taken when the last point repeats the
  // first.
  bool closed = false;
};

struct ToolFrameOptions {
  // Roll limit (issue 19, reachability): when > 0 and below pi, x is kept within this angle of `preferred_x`
  // (projected off z) by turning it about z; rad. 0: off (x = travel).
  double roll_cone_rad = 0.0;
  Eigen::Vector3d preferred_x = Eigen::Vector3d::UnitX();  // in the path's frame; any length > 0
  // A step between consecutive points of a segment longer than this many times the segment's median step (and than
  // 1 mm) is a broken file, not a move (a 15 m jump between 8 mm steps): refused (job_paths.h). 0: no check.
  double max_jump_ratio = 50.0;

  bool IsValid(std::string* error) const;
};

struct ToolFrameFigures {
  double max_orientation_step_rad = 0.0;  // largest rotation angle between consecutive frames of a segment
  std::size_t max_step_index = 0;         // frame index (over the whole path, from 0) after that step
  std::size_t parallel_tangents = 0;      // frames whose tangent was parallel to z (or missing): x carried over
  std::size_t repeated_points = 0;        // points equal to their predecessor
  std::size_t roll_limited = 0;           // frames whose x was turned into the roll cone
};

// Frames for one segment. Throws conform::Error when sizes differ, a value is not finite or a tool axis is zero.
std::vector<ToolFrame> build_tool_frames(const ToolPathPoints& points, const ToolFrameOptions& options,
                                         ToolFrameFigures* figures = nullptr);

// The rotation angle between two rotations, rad, in [0, pi].
double rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

// Largest orientation change between consecutive frames of each segment (figures.max_*).
void measure_orientation_steps(const ToolPath& path, ToolFrameFigures* figures);

}  // namespace conform
