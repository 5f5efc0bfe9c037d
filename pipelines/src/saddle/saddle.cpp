#include "conform/pipelines/saddle/saddle.h"

#include <string>

#include "conform/core/atomic_file.h"
#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform {
SaddleStepRule constant_speed_rule(const SaddleGeometry& geometry) {
  const bool papers_joint = geometry.pitch_rad == kHalfPi && geometry.offset_mm == 0.0;
  return papers_joint ? SaddleStepRule::kVariableAngle : SaddleStepRule::kArcLength;
}

std::string saddle_csv(const SaddleResult& result) {
  constexpr int kRadDecimals = 12;
  constexpr int kMmDecimals = 9;
  std::string csv = "i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm\n";
  csv.reserve(csv.size() + result.points.size() * 96);
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    const SaddlePoint& point = result.points[i];
    csv += std::to_string(i);
    csv += ',';
    csv += format_fixed(point.theta_rad, kRadDecimals);
    for (int axis = 0; axis < 3; ++axis) {
      csv += ',';
      csv += format_fixed(point.position[axis], kMmDecimals);
    }
    csv += ',';
    csv += format_fixed(point.pose_rad, kRadDecimals);
    csv += ',';
    csv += format_fixed(point.step_mm, kMmDecimals);
    csv += '\n';
  }
  return csv;
}

SaddleJobResult run_saddle(const SaddleJobOptions& options) {
  SaddleJobResult result;
  result.saddle = interpolate_saddle(options.saddle);  // throws conform::Error on bad input
  if (!options.out_path.empty() && result.saddle.converged) {
    write_file_atomically(options.out_path, saddle_csv(result.saddle));
    result.out_path = options.out_path;
  }
  return result;
}

}  // namespace conform
