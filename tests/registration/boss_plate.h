#pragma once
// The near-symmetric plate of the coarse-alignment tests: turned 180 degrees it fits all but its one small boss.

#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace conform::test {

// A 120 x 80 x 10 mm plate (grid points on its six faces, `step` apart, shifted by `offset` within the grid) with a
// boss of radius 6 mm and height 5 mm on its top face near one corner: the only thing that breaks its symmetry.
inline std::vector<Eigen::Vector3d> boss_plate(double step, double offset) {
  const Eigen::Vector3d size(120, 80, 10);
  const Eigen::Vector2d boss(40, 22);
  const double boss_r = 6.0, boss_h = 5.0;
  std::vector<Eigen::Vector3d> out;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double side : {-0.5, 0.5}) {
      for (double s = -0.5 * size(u) + offset; s <= 0.5 * size(u); s += step) {
        for (double t = -0.5 * size(v) + offset; t <= 0.5 * size(v); t += step) {
          Eigen::Vector3d p;
          p(axis) = side * size(axis);
          p(u) = s;
          p(v) = t;
          if (axis == 2 && side > 0 && (p.head<2>() - boss).norm() < boss_r) continue;  // under the boss
          out.push_back(p);
        }
      }
    }
  }
  const double top = 0.5 * size.z();
  for (double a = offset / boss_r; a < 2.0 * M_PI; a += step / boss_r) {
    for (double z = top + offset; z <= top + boss_h; z += step) {
      out.emplace_back(boss.x() + boss_r * std::cos(a), boss.y() + boss_r * std::sin(a), z);
    }
  }
  for (double x = -boss_r + offset; x <= boss_r; x += step) {
    for (double y = -boss_r + offset; y <= boss_r; y += step) {
      if (x * x + y * y <= boss_r * boss_r) out.emplace_back(boss.x() + x, boss.y() + y, top + boss_h);
    }
  }
  return out;
}

}  // namespace conform::test
