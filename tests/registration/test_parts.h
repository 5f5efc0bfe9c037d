#pragma once
// The three generated parts the registration tests run on, each as a reference and a differently meshed, noisy scan
// of the same surface (world frame): a tube patch, the box part with features, the free-form surface.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/geometry.h"
#include "conform/datasets/parts.h"
#include "conform/datasets/tube.h"
#include "registration_test_util.h"

namespace conform::test {

enum class PartKind { kTubePatch, kBox, kFreeform };

struct TestPart {
  std::string name;
  PartKind kind = PartKind::kBox;
  Mesh reference;                                    // 4 mm edges, exact
  std::vector<Eigen::Vector3d> scan;                 // 3 mm edges, 0.02 mm noise along the normals, world frame
  double size_mm = 0.0;                              // bounding-box diagonal of the reference
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of the scan
  // The tube's axis (world), for the errors that the tube constrains.
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();
};

inline TestPart make_test_part(PartKind kind, std::uint64_t seed = 7) {
  TestPart part;
  part.kind = kind;
  if (kind == PartKind::kTubePatch) {
    part.name = "tube patch";
    TubeOptions tube;
    tube.radius_mm = 150.0;
    tube.length_mm = 200.0;
    tube.arc_rad = M_PI / 3.0;
    tube.edge_mm = 4.0;
    part.reference = generate_tube(tube).mesh;
    tube.edge_mm = 3.0;
    tube.noise_mm = 0.02;
    tube.seed = seed;
    part.scan = generate_tube(tube).mesh.vertices;
  } else {
    PartOptions options;
    options.edge_mm = 4.0;
    const bool box = kind == PartKind::kBox;
    part.name = box ? "box part" : "free-form";
    part.reference = box ? box_part(options) : freeform_surface(options);
    options.edge_mm = 3.0;
    options.noise_mm = 0.02;
    options.seed = seed;
    part.scan = (box ? box_part(options) : freeform_surface(options)).vertices;
  }
  part.size_mm = bounding_box(part.reference).diagonal();
  part.centre = mean_point(part.scan);
  return part;
}

// How far an estimate is from the truth, in what the part constrains: everything for the box and the free-form
// surface; for the tube, the axis (its direction and its offset), since sliding along and turning about it are
// degenerate (and the axis' direction, since a patch turned end for end is the same surface).
struct PoseError {
  double rotation_deg = 0.0;
  double translation_mm = 0.0;
};

inline PoseError pose_error(const TestPart& part, const Eigen::Isometry3d& est, const Eigen::Isometry3d& truth) {
  if (part.kind != PartKind::kTubePatch) return {rotation_error_deg(est, truth), translation_error_mm(est, truth)};
  // E maps the truly aligned scan to where the estimate put it; it should map the axis onto itself.
  const Eigen::Isometry3d E = est * truth.inverse();
  const Eigen::Vector3d d = part.axis_direction.normalized();
  const Eigen::Vector3d moved_dir = E.linear() * d;
  const Eigen::Vector3d moved_point = E * part.axis_point;
  const Eigen::Vector3d off = moved_point - part.axis_point;
  PoseError e;
  // The axis as a line: a patch turned end for end about its normal is the same surface (a symmetry).
  e.rotation_deg = std::acos(std::min(1.0, std::abs(moved_dir.dot(d)))) / kDeg;
  e.translation_mm = (off - off.dot(d) * d).norm();
  return e;
}

}  // namespace conform::test
