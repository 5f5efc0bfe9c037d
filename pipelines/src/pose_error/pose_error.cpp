#include "conform/pipelines/pose_error/pose_error.h"

#include <cmath>

#include "conform/core/error.h"
#include "conform/core/transform_io.h"

namespace conform {

PoseErrorResult run_pose_error(const PoseErrorOptions& options) {
  if (!(std::isfinite(options.mm_per_unit) && options.mm_per_unit > 0.0)) {
    throw Error("millimetres per unit must be finite and > 0");
  }
  PoseErrorResult result;
  result.a = read_transform(options.path_a);
  result.b = read_transform(options.path_b);
  result.a.translation() *= options.mm_per_unit;
  result.b.translation() *= options.mm_per_unit;
  result.error = pose_error(result.a, result.b);
  return result;
}

}  // namespace conform
