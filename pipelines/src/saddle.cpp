#include "conform/pipelines/saddle.h"

#include <cstdio>
#include <string>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// Fixed decimals; a value that rounds to zero is written without a sign, so that -1e-15 and 1e-15 give the same bytes.
void append_fixed(std::string* out, double value, int decimals) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  const char* text = buffer;
  if (buffer[0] == '-') {
    bool all_zero = true;
    for (int i = 1; i < n; ++i) all_zero = all_zero && (buffer[i] == '0' || buffer[i] == '.');
    if (all_zero) text = buffer + 1;
  }
  out->append(text);
}

}  // namespace

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
    append_fixed(&csv, point.theta_rad, kRadDecimals);
    for (int axis = 0; axis < 3; ++axis) {
      csv += ',';
      append_fixed(&csv, point.position[axis], kMmDecimals);
    }
    csv += ',';
    append_fixed(&csv, point.pose_rad, kRadDecimals);
    csv += ',';
    append_fixed(&csv, point.step_mm, kMmDecimals);
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
