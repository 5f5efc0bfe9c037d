#include "conform/pipelines/pose_error/pose_error_json.h"

#include <cmath>

namespace conform {

nlohmann::json pose_error_json(const PoseErrorOptions& options, const PoseErrorResult& result) {
  return {{"transform_a", options.path_a},
          {"transform_b", options.path_b},
          {"rotation_deg", result.error.rotation_rad * 180.0 / M_PI},
          {"translation_mm", result.error.translation_mm}};
}

}  // namespace conform
