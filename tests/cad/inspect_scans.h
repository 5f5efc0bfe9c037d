#pragma once
// Scans of generated parts for the `conform inspect` tests: known errors of holes, the scan written to the last bit,
// the part as STEP, the inspection in the part frame.

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cad_shapes.h"
#include "conform/core/cad_faces.h"
#include "conform/core/io.h"
#include "conform/core/mesh.h"
#include "conform/pipelines/inspect/inspect.h"

namespace conform::test {

// A hole along z as made: its nominal centre (x, y) and radius, the radius it was made to exceed by, and how far its
// axis was moved (x, y).
struct MadeHole {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_mm = 0.0;
  double oversize_mm = 0.0;
  Eigen::Vector2d shift_mm = Eigen::Vector2d::Zero();
};

// The error of the made hole's wall at p (a point on the nominal wall) along the nominal wall's outward normal
// (towards the axis: a hole's outside is its air), mm. Along the radial direction u from the nominal axis the made
// wall (radius R', axis moved by s) is at r = s.u + sqrt(R'^2 - |s|^2 + (s.u)^2); material removed is -.
inline double hole_error(const MadeHole& hole, const Eigen::Vector3d& p) {
  const Eigen::Vector2d u = (p.head<2>() - hole.centre).normalized();
  const double su = hole.shift_mm.dot(u), made = hole.radius_mm + hole.oversize_mm;
  return -(su + std::sqrt(made * made - hole.shift_mm.squaredNorm() + su * su) - hole.radius_mm);
}

inline double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (const double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

// The shape written as STEP in mm at `path`, and its faces as inspect reads them.
inline CadFaces write_step(const TopoDS_Shape& shape, const std::string& path) {
  write_cad(shape, path, CadFormat::kStep, "MM");
  return read_cad_faces(path, CadReadOptions{}, nullptr, nullptr);
}

// run_inspect on `scan` against `step` in the part frame, with the defaults.
inline InspectResult inspect_in_part_frame(const std::string& scan, const std::string& step) {
  InspectOptions options;
  options.scan_path = scan;
  options.reference_path = step;
  return run_inspect(options);
}

}  // namespace conform::test
