#pragma once
// Are the cutting and welding tools clear of the material? Each tool tip p - s d and its approach line (the segment
// from the tip to the seam point p) is checked against the tubes' walls, modelled at each path point from the scans:
//
//   stub wall    radial distance from the stub axis (z_S) in (rho_p, rho_p + d_s), rho_p that of the seam point p
//                (the scan is the stub's inner surface); for the weld, only its part left after the cut: the side of
//                the cut face (the plane through p spanned by t and d_c) that holds the wall (Eq. 7).
//   leg          radial distance from the leg axis below R_p, that of p (the scan is the leg's outer surface): solid
//                for the test (a torch behind the leg wall is as unreachable as one in it), so d_l is not needed for
//                outside welds; it is accepted for the inside grooves of mixed joints, which are not modelled.
//   groove       a cut needs alpha_c < psi (the dihedral angle, tool_paths.h): otherwise d_c runs into the stub's
//                hollow and the "groove" would remove the wall's end. Checked without wall thicknesses too.
//
// The cut is made on the stub alone (before fit-up), so the cutting torch is checked against the whole stub wall;
// the weld torch against the cut stub and the leg. Points of an approach line within `seam_clearance_mm` of p are
// not tested (they touch both surfaces at the seam). Local models: valid for standoffs far smaller than the radii.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/intersection/joint_geometry.h"
#include "conform/toolpath/intersection/tool_paths.h"

namespace conform {

struct ToolSafetyOptions {
  double stub_wall_mm = 0.0;       // d_s, mm; 0: the wall thickness is unknown, the stub wall is not checked
  double leg_wall_mm = 0.0;        // d_l, mm; not used by the outside-weld checks (above); >= 0
  double seam_clearance_mm = 0.5;  // mm, > 0
  int line_samples = 32;           // points tested along each approach line, >= 2

  bool IsValid(std::string* error) const;
};

// One kind of violation: how many path points, and the first.
struct ToolViolation {
  std::size_t count = 0;
  double first_phi_rad = 0.0;
  Eigen::Vector3d first_where = Eigen::Vector3d::Zero();  // the offending tip or line point, mm
};

struct ToolSafetyResult {
  bool ok = true;
  bool walls_checked = false;           // stub_wall_mm > 0
  ToolViolation groove_beyond_wall;     // alpha_c >= psi
  ToolViolation cut_tip_in_stub;        // the cutting torch's tip inside the stub wall
  ToolViolation cut_line_in_stub;       // its approach line crosses the stub wall
  ToolViolation weld_tip_in_stub;       // the weld torch's tip inside the (cut) stub wall
  ToolViolation weld_tip_in_leg;        // the weld torch's tip below the leg's surface
  ToolViolation weld_line_in_material;  // its approach line crosses the stub wall or the leg
  std::string message;                  // empty when ok: what fails, where, and what to change
};

// frames and tools of the same path (tool_paths.h); leg_axis in S. Throws conform::Error for invalid options or
// sizes that differ.
ToolSafetyResult check_tool_safety(const std::vector<PathFrame>& frames, const ToolPaths& tools,
                                   const TubeAxis& leg_axis, const ToolPathOptions& tool_options,
                                   const ToolSafetyOptions& options);

}  // namespace conform
