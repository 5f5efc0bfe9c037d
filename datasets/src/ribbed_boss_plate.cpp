#include "conform/datasets/ribbed_boss_plate.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conform/core/error.h"

namespace conform {

double ribbed_plate_boss_height(double x_mm, double y_mm) {
  const double t = std::clamp((10.0 - std::hypot(x_mm + 70.0, y_mm - 45.0)) / 2.0, 0.0, 1.0);
  return 4.0 * t * t * (3.0 - 2.0 * t);
}

Mesh ribbed_boss_plate_mesh(const RibbedPlateOptions& options, double spacing_mm) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("ribbed boss plate: " + why);
  if (!(spacing_mm > 0.0) || !std::isfinite(spacing_mm)) throw Error("ribbed boss plate: the spacing must be > 0");
  const int nx = static_cast<int>(std::lround(options.length_mm / spacing_mm)) + 1;
  const int ny = static_cast<int>(std::lround(options.width_mm / spacing_mm)) + 1;
  Mesh mesh;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = -0.5 * options.length_mm + options.length_mm * i / (nx - 1);
      const double y = -0.5 * options.width_mm + options.width_mm * j / (ny - 1);
      mesh.vertices.emplace_back(x, y, ribbed_plate_height(options, x, y) + ribbed_plate_boss_height(x, y));
    }
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      mesh.faces.push_back({a, b, d});
      mesh.faces.push_back({a, d, c});
    }
  }
  return mesh;
}

}  // namespace conform
