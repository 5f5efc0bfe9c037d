#pragma once
// A saddle joint for the saddle tests: leg radius R, pipe radius r (mm), pitch (deg), offset (mm).

#include "conform/core/constants.h"
#include "conform/toolpath/saddle/saddle_curve.h"

namespace conform::test {

inline SaddleGeometry saddle_geometry(double R, double r, double pitch_deg, double offset) {
  SaddleGeometry g;
  g.leg_radius_mm = R;
  g.pipe_radius_mm = r;
  g.pitch_rad = pitch_deg / 180.0 * kPi;
  g.offset_mm = offset;
  return g;
}

}  // namespace conform::test
