#pragma once
// `conform saddle`: the interpolated saddle-shaped weld path of a pipe on a cylinder, with the torch pose angle
// (Xue et al. 2018, generalised to any pitch and offset; toolpath/saddle/saddle.h), written as CSV.

#include <string>

#include "conform/toolpath/saddle/saddle.h"

namespace conform {

struct SaddleJobOptions {
  SaddleOptions saddle;  // geometry, start pose, step rule and its step or speed and period (toolpath/saddle/saddle.h)
  std::string out_path;  // CSV to write, whole or not at all; empty: write nothing
};

struct SaddleJobResult {
  SaddleResult saddle;
  std::string out_path;  // the file written; empty when none was asked for or the interpolation did not converge
};

// The constant-speed rule for a joint: the paper's variable-angle interpolation (Eq. 24) for the paper's joint
// (pitch pi/2, offset 0), exact arc-length steps for any other.
SaddleStepRule constant_speed_rule(const SaddleGeometry& geometry);

// Throws conform::Error with a message naming the bad value (r >= R, a radius, speed, period or step that is not
// positive, a pitch outside (0, 90] deg, an offset too large for the pipe to meet the cylinder, ...), or naming the
// output file when it cannot be written. A failed run leaves no output file.
SaddleJobResult run_saddle(const SaddleJobOptions& options);

// The CSV: header `i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm`, one row per point, fixed decimals (12 for radians,
// 9 for millimetres), '\n' line ends; the same result gives the same bytes.
std::string saddle_csv(const SaddleResult& result);

}  // namespace conform
