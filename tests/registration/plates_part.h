#pragma once
// A part of thin plates for the tests of one-side scans: a base, an upright and two ribs of different heights, all
// `thickness` mm thick, sampled uniformly on its outer surface (on every face: the reference), or only on the faces
// that look towards a scanner (a scan from one side).

#include <vector>

#include <Eigen/Geometry>

#include "conform/core/random.h"

namespace conform::test {

inline std::vector<Eigen::AlignedBox3d> plate_boxes(double thickness) {
  const double t = thickness;
  return {
      Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(120, 80, t)),       // base
      Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, t), Eigen::Vector3d(120, t, 70)),       // upright
      Eigen::AlignedBox3d(Eigen::Vector3d(25, t, t), Eigen::Vector3d(25 + t, 60, 50)),  // tall rib
      Eigen::AlignedBox3d(Eigen::Vector3d(80, t, t), Eigen::Vector3d(80 + t, 40, 30)),  // short rib
  };
}

// Points uniform on the part's outer surface (the faces of its boxes outside the other boxes), about `density` per
// mm^2, with `noise` mm along each axis; with `towards` non-zero only those whose outward normal has a cosine above
// 0.3 with it (a scan from one side).
inline std::vector<Eigen::Vector3d> plates_surface(double thickness, double density, double noise,
                                                   const Eigen::Vector3d& towards, Random& random) {
  const std::vector<Eigen::AlignedBox3d> boxes = plate_boxes(thickness);
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::AlignedBox3d& box : boxes) {
    const Eigen::Vector3d size = box.sizes();
    for (int axis = 0; axis < 3; ++axis) {
      for (const int side : {-1, 1}) {
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        normal[axis] = side;
        if (towards.norm() > 0.0 && normal.dot(towards.normalized()) <= 0.3) continue;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const auto count = static_cast<int>(density * size[u] * size[v]);
        for (int k = 0; k < count; ++k) {
          Eigen::Vector3d p;
          p[axis] = side < 0 ? box.min()[axis] : box.max()[axis];
          p[u] = box.min()[u] + random.uniform(0.0, size[u]);
          p[v] = box.min()[v] + random.uniform(0.0, size[v]);
          bool inside = false;  // covered by another box: not on the part's surface
          for (const Eigen::AlignedBox3d& other : boxes) {
            if (&other == &box) continue;
            inside = inside ||
                     ((p.array() > other.min().array() - 1e-9).all() && (p.array() < other.max().array() + 1e-9).all());
          }
          if (inside) continue;
          out.push_back(p + noise * Eigen::Vector3d(random.normal(), random.normal(), random.normal()));
        }
      }
    }
  }
  return out;
}

}  // namespace conform::test
