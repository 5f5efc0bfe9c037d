#include "conform/toolpath/tool_paths.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kHalfPi = kPi / 2;

bool is_angle(double a) { return std::isfinite(a) && std::abs(a) < kHalfPi; }

}  // namespace

bool ToolPathOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  for (std::size_t i = 0; i < 4; ++i) {
    if (!is_angle(groove_rad[i])) {
      why << "groove angle " << i + 1 << " (" << groove_rad[i] * 180.0 / kPi << " deg) is outside (-90, 90) deg";
      break;
    }
  }
  if (why.tellp() == 0) {
    if (!is_angle(weld_angle_rad))
      why << "weld angle " << weld_angle_rad * 180.0 / kPi << " deg is outside (-90, 90) deg";
    else if (!(std::isfinite(cut_standoff_mm) && cut_standoff_mm >= 0.0))
      why << "cut standoff " << cut_standoff_mm << " mm must be >= 0";
    else if (!(std::isfinite(weld_standoff_mm) && weld_standoff_mm >= 0.0))
      why << "weld standoff " << weld_standoff_mm << " mm must be >= 0";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

double groove_angle(const std::array<double, 4>& quarters_rad, GrooveInterpolation interpolation, double phi_rad) {
  double phi = std::fmod(phi_rad, 2.0 * kPi);
  if (phi < 0.0) phi += 2.0 * kPi;
  const double position = phi / kHalfPi;
  const auto i = std::min<std::size_t>(3, static_cast<std::size_t>(position));
  double u = position - static_cast<double>(i);
  if (interpolation == GrooveInterpolation::kQuadratic) u = u < 0.5 ? 2.0 * u * u : 1.0 - 2.0 * (1.0 - u) * (1.0 - u);
  const double a0 = quarters_rad[i];
  const double a1 = quarters_rad[(i + 1) % 4];
  return a0 + (a1 - a0) * u;
}

Eigen::Vector3d rotate_about(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, axis) * v;
}

ToolPaths tool_paths(const std::vector<PathFrame>& frames, const ToolPathOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tool paths: " + why);
  ToolPaths paths;
  for (const PathFrame& f : frames) {
    const double alpha_c = groove_angle(options.groove_rad, options.interpolation, f.phi_rad);
    const Eigen::Vector3d d_c = rotate_about(f.leg_out, f.tangent, alpha_c).normalized();  // Eq. (7)
    paths.cut.push_back({f.phi_rad, f.point - options.cut_standoff_mm * d_c, d_c});        // Eq. (9), (10)
    const Eigen::Vector3d d_w = rotate_about(-f.leg_out, f.tangent, options.weld_angle_rad).normalized();
    paths.weld.push_back({f.phi_rad, f.point - options.weld_standoff_mm * d_w, d_w});  // Eq. (11)
    paths.groove_rad.push_back(alpha_c);
  }
  return paths;
}

}  // namespace conform
