#include "conform/toolpath/intersection/tool_paths.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {


bool is_angle(double a) { return std::isfinite(a) && a >= 0.0 && a < kHalfPi; }

}  // namespace

GrooveTable ToolPathOptions::groove() const {
  if (!groove_table_rad.empty()) return GrooveTable(groove_table_rad, interpolation);
  return GrooveTable::quarters(groove_rad[0], groove_rad[1], groove_rad[2], groove_rad[3], interpolation);
}

bool ToolPathOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (groove_table_rad.empty()) {
    for (std::size_t i = 0; i < 4; ++i) {
      if (!is_angle(groove_rad[i])) {
        why << "groove angle " << i + 1 << " (" << groove_rad[i] * 180.0 / kPi << " deg) is outside [0, 90) deg";
        break;
      }
    }
  }
  std::string table_why;
  if (why.tellp() == 0 && !groove().IsValid(&table_why)) why << table_why;
  if (why.tellp() == 0) {
    if (!is_angle(weld_angle_rad))
      why << "weld angle " << weld_angle_rad * 180.0 / kPi
          << " deg is outside [0, 90) deg (a negative angle puts the torch inside the leg)";
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
  return GrooveTable::quarters(quarters_rad[0], quarters_rad[1], quarters_rad[2], quarters_rad[3], interpolation)
      .at(phi_rad);
}

double dihedral_angle(const PathFrame& f) {
  Eigen::Vector3d u = f.tangent.cross(f.stub_normal);
  if (u.z() > 0.0) u = -u;  // away from the leg: towards the stub's distal end (z_S points at the leg)
  return std::atan2(u.dot(f.leg_normal), u.dot(f.leg_out));
}

Eigen::Vector3d rotate_about(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, axis) * v;
}

ToolPaths tool_paths(const std::vector<PathFrame>& frames, const ToolPathOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tool paths: " + why);
  ToolPaths paths;
  paths.weld_angle_rad = options.weld_angle_rad;
  const GrooveTable groove = options.groove();
  for (const PathFrame& f : frames) {
    const double alpha_c = groove.at(f.phi_rad);
    const Eigen::Vector3d d_c = rotate_about(f.leg_out, f.tangent, alpha_c).normalized();  // Eq. (7)
    paths.cut.push_back({f.phi_rad, f.point - options.cut_standoff_mm * d_c, d_c});        // Eq. (9), (10)
    const Eigen::Vector3d d_w = rotate_about(-f.leg_out, f.tangent, options.weld_angle_rad).normalized();
    paths.weld.push_back({f.phi_rad, f.point - options.weld_standoff_mm * d_w, d_w});  // Eq. (11)
    paths.groove_rad.push_back(alpha_c);
    paths.psi_rad.push_back(dihedral_angle(f));
  }
  return paths;
}

}  // namespace conform
