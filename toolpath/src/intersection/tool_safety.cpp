#include "conform/toolpath/intersection/tool_safety.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {


double radial(const Eigen::Vector3d& x, const TubeAxis& axis) {
  const Eigen::Vector3d d = x - axis.point;
  return (d - d.dot(axis.direction) * axis.direction).norm();
}

void count(ToolViolation* v, double phi, const Eigen::Vector3d& where) {
  if (v->count++ == 0) {
    v->first_phi_rad = phi;
    v->first_where = where;
  }
}

// The material model at one path point.
struct LocalWalls {
  Eigen::Vector3d p;
  double rho_p = 0.0;          // from the stub axis
  double r_leg_p = 0.0;        // from the leg axis
  double stub_wall = 0.0;      // 0: unknown
  Eigen::Vector3d cut_normal;  // normal of the cut face (t x d_c), oriented towards the wall that is left
  TubeAxis leg_axis;

  bool in_stub_wall(const Eigen::Vector3d& x) const {
    if (stub_wall <= 0.0) return false;
    const double rho = x.head<2>().norm();
    return rho > rho_p && rho < rho_p + stub_wall;
  }
  bool in_cut_stub_wall(const Eigen::Vector3d& x) const { return in_stub_wall(x) && (x - p).dot(cut_normal) > 0.0; }
  bool in_leg(const Eigen::Vector3d& x) const { return radial(x, leg_axis) < r_leg_p; }
};

// Whether a point of the approach line from tip to p (the seam's neighbourhood left out) is in the material.
template <typename Inside>
bool line_hits(const Eigen::Vector3d& tip, const Eigen::Vector3d& p, const ToolSafetyOptions& o, Inside inside,
               Eigen::Vector3d* where) {
  const double length = (p - tip).norm();
  if (length <= o.seam_clearance_mm) return false;
  for (int k = 0; k < o.line_samples; ++k) {
    const double s = (length - o.seam_clearance_mm) * k / (o.line_samples - 1);
    const Eigen::Vector3d x = tip + s / length * (p - tip);
    if (inside(x)) {
      *where = x;
      return true;
    }
  }
  return false;
}

std::string describe(const char* what, const ToolViolation& v, std::size_t points, const char* advice) {
  char text[400];
  std::snprintf(text, sizeof text, "%s at %zu of %zu points (first at azimuth %.1f deg, (%.3f, %.3f, %.3f) mm): %s",
                what, v.count, points, v.first_phi_rad * kDegPerRad, v.first_where.x(), v.first_where.y(), v.first_where.z(),
                advice);
  return text;
}

// What failed, where, and what to change, one sentence per kind.
std::vector<std::string> describe_all(const ToolSafetyResult& r, std::size_t n, const ToolPathOptions& tool_options) {
  char advice[300];
  std::vector<std::string> problems;
  if (r.groove_beyond_wall.count > 0) {
    problems.push_back(
        describe("the groove angle reaches the dihedral angle between leg and stub wall (the cut would "
                 "run into the stub's hollow)",
                 r.groove_beyond_wall, n, "lower the groove angle there"));
  }
  if (r.weld_tip_in_stub.count > 0) {
    std::snprintf(advice, sizeof advice,
                  "the weld angle %.1f deg must stay below the groove angle wherever the torch is to point into the "
                  "groove, or the standoff must exceed d_s / sin(psi - alpha_w)",
                  tool_options.weld_angle_rad * kDegPerRad);
    problems.push_back(describe("the weld torch's tip lies inside the stub wall", r.weld_tip_in_stub, n, advice));
  }
  if (r.weld_tip_in_leg.count > 0) {
    problems.push_back(describe("the weld torch's tip lies below the leg's surface", r.weld_tip_in_leg, n,
                                "raise the weld angle or shorten the standoff"));
  }
  if (r.cut_tip_in_stub.count > 0) {
    problems.push_back(describe("the cutting torch's tip lies inside the stub wall", r.cut_tip_in_stub, n,
                                "check the groove angles and the cut standoff"));
  }
  if (r.cut_line_in_stub.count > 0) {
    problems.push_back(describe("the cutting torch's approach line crosses the stub wall", r.cut_line_in_stub, n,
                                "shorten the cut standoff"));
  }
  if (r.weld_line_in_material.count > 0) {
    problems.push_back(describe("the weld torch's approach line crosses the stub wall or the leg",
                                r.weld_line_in_material, n, "change the weld angle or standoff"));
  }
  return problems;
}

}  // namespace

bool ToolSafetyOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(std::isfinite(stub_wall_mm) && stub_wall_mm >= 0.0))
    why << "stub wall " << stub_wall_mm << " mm must be >= 0";
  else if (!(std::isfinite(leg_wall_mm) && leg_wall_mm >= 0.0))
    why << "leg wall " << leg_wall_mm << " mm must be >= 0";
  else if (!(seam_clearance_mm > 0.0))
    why << "seam clearance must be > 0 mm";
  else if (line_samples < 2)
    why << "line samples must be >= 2";
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

ToolSafetyResult check_tool_safety(const std::vector<PathFrame>& frames, const ToolPaths& tools,
                                   const TubeAxis& leg_axis, const ToolPathOptions& tool_options,
                                   const ToolSafetyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tool safety: " + why);
  if (tools.cut.size() != frames.size() || tools.weld.size() != frames.size() || tools.psi_rad.size() != frames.size())
    throw Error("tool safety: the tool paths and the path frames differ in length");
  ToolSafetyResult r;
  r.walls_checked = options.stub_wall_mm > 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const PathFrame& f = frames[i];
    LocalWalls w;
    w.p = f.point;
    w.rho_p = f.point.head<2>().norm();
    w.leg_axis = leg_axis;
    w.r_leg_p = radial(f.point, leg_axis);
    w.stub_wall = options.stub_wall_mm;
    Eigen::Vector3d u = f.tangent.cross(f.stub_normal);
    if (u.z() > 0.0) u = -u;
    w.cut_normal = f.tangent.cross(tools.cut[i].direction);
    if (w.cut_normal.dot(u) < 0.0) w.cut_normal = -w.cut_normal;
    if (tools.groove_rad[i] >= tools.psi_rad[i]) count(&r.groove_beyond_wall, f.phi_rad, f.point);
    const Eigen::Vector3d& cut_tip = tools.cut[i].position;
    const Eigen::Vector3d& weld_tip = tools.weld[i].position;
    Eigen::Vector3d where;
    if (w.in_stub_wall(cut_tip))
      count(&r.cut_tip_in_stub, f.phi_rad, cut_tip);
    else if (line_hits(
                 cut_tip, f.point, options, [&](const Eigen::Vector3d& x) { return w.in_stub_wall(x); }, &where))
      count(&r.cut_line_in_stub, f.phi_rad, where);
    const bool weld_in_stub = w.in_cut_stub_wall(weld_tip);
    const bool weld_in_leg = w.in_leg(weld_tip);
    if (weld_in_stub) count(&r.weld_tip_in_stub, f.phi_rad, weld_tip);
    if (weld_in_leg) count(&r.weld_tip_in_leg, f.phi_rad, weld_tip);
    if (!weld_in_stub && !weld_in_leg &&
        line_hits(
            weld_tip, f.point, options, [&](const Eigen::Vector3d& x) { return w.in_cut_stub_wall(x) || w.in_leg(x); },
            &where))
      count(&r.weld_line_in_material, f.phi_rad, where);
  }
  const std::vector<std::string> problems = describe_all(r, frames.size(), tool_options);
  r.ok = problems.empty();
  for (std::size_t k = 0; k < problems.size(); ++k) r.message += (k > 0 ? "; " : "") + problems[k];
  return r;
}

}  // namespace conform
