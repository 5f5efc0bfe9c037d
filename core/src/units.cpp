#include "conform/core/units.h"

#include <cctype>
#include <cmath>

#include "conform/core/error.h"

namespace conform {

double millimetres_per_unit(const std::string& unit) {
  std::string u;
  for (char c : unit) u += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (u == "mm") return 1.0;
  if (u == "cm") return 10.0;
  if (u == "m") return 1000.0;
  if (u == "in") return 25.4;
  throw Error("unknown length unit '" + unit + "' (use mm, cm, m or in)");
}

namespace {
void check_factor(double factor) {
  if (!std::isfinite(factor) || factor <= 0.0) throw Error("scale factor must be finite and positive");
}
}  // namespace

void scale_in_place(Cloud& cloud, double factor) {
  check_factor(factor);
  for (pcl::PointXYZ& p : cloud.points) {
    p.getVector3fMap() = (p.getVector3fMap().cast<double>() * factor).cast<float>();
  }
}

void scale_in_place(Mesh& mesh, double factor) {
  check_factor(factor);
  for (Eigen::Vector3d& p : mesh.vertices) p *= factor;
}

}  // namespace conform
