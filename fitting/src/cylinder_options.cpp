#include <cmath>
#include <string>

#include "conform/core/constants.h"
#include "conform/fitting/cylinder.h"

namespace conform {
namespace {

bool fail(std::string* error, const std::string& why) {
  if (error != nullptr) *error = why;
  return false;
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

const char* to_string(CylinderFailure failure) {
  switch (failure) {
    case CylinderFailure::kNone:
      return "none";
    case CylinderFailure::kNoConsensus:
      return "no consensus";
    case CylinderFailure::kPlane:
      return "plane";
    case CylinderFailure::kSphere:
      return "sphere";
    case CylinderFailure::kRadiusAtBound:
      return "radius at bound";
    case CylinderFailure::kAxisOutsidePrior:
      return "axis outside prior";
    case CylinderFailure::kNotConverged:
      return "not converged";
  }
  return "unknown";
}

const char* to_string(CylinderSide side) {
  switch (side) {
    case CylinderSide::kOuter:
      return "outer";
    case CylinderSide::kInner:
      return "inner";
    case CylinderSide::kUnknown:
      return "unknown";
  }
  return "unknown";
}

bool CylinderFitOptions::IsValid(std::string* error) const {
  if (!(threshold_mm >= 0.0) || !std::isfinite(threshold_mm)) {
    return fail(error, "threshold_mm must be >= 0 (0: automatic), got " + std::to_string(threshold_mm));
  }
  if (!positive(inlier_sigmas)) return fail(error, "inlier_sigmas must be > 0");
  if (!(normal_threshold_rad > 0.0 && normal_threshold_rad <= kHalfPi)) {
    return fail(error, "normal_threshold_rad must be in (0, pi/2]");
  }
  if (!(min_radius_mm >= 0.0) || !std::isfinite(min_radius_mm)) return fail(error, "min_radius_mm must be >= 0");
  if (!(max_radius_mm > min_radius_mm)) {
    return fail(error, "max_radius_mm (" + std::to_string(max_radius_mm) + ") must exceed min_radius_mm (" +
                           std::to_string(min_radius_mm) + ")");
  }
  if (!axis_prior.allFinite()) return fail(error, "axis_prior must be finite");
  if (!(axis_prior_tolerance_rad > 0.0 && axis_prior_tolerance_rad <= kHalfPi)) {
    return fail(error, "axis_prior_tolerance_rad must be in (0, pi/2]");
  }
  if (ransac_max_iterations < 1 || ransac_min_iterations < 0 || ransac_min_iterations > ransac_max_iterations) {
    return fail(error, "ransac iterations: need 0 <= ransac_min_iterations <= ransac_max_iterations, max >= 1");
  }
  if (!(ransac_confidence > 0.0 && ransac_confidence < 1.0)) return fail(error, "ransac_confidence must be in (0, 1)");
  if (ransac_sample_points < 2) return fail(error, "ransac_sample_points must be >= 2");
  if (!(min_normal_angle_rad >= 0.0 && min_normal_angle_rad < kHalfPi)) {
    return fail(error, "min_normal_angle_rad must be in [0, pi/2)");
  }
  if (refine_rounds < 1) return fail(error, "refine_rounds must be >= 1");
  if (!positive(loss_sigmas)) return fail(error, "loss_sigmas must be > 0");
  if (max_solver_iterations < 1) return fail(error, "max_solver_iterations must be >= 1");
  if (!positive(solver_tolerance)) return fail(error, "solver_tolerance must be > 0");
  if (!(min_inlier_fraction >= 0.0 && min_inlier_fraction <= 1.0)) {
    return fail(error, "min_inlier_fraction must be in [0, 1]");
  }
  if (!(min_sagitta_sigmas >= 0.0) || !std::isfinite(min_sagitta_sigmas)) {
    return fail(error, "min_sagitta_sigmas must be >= 0");
  }
  if (!(sphere_ratio >= 0.0 && sphere_ratio <= 1.0)) return fail(error, "sphere_ratio must be in [0, 1]");
  if (!(max_shape_ambiguity_mm >= 0.0)) return fail(error, "max_shape_ambiguity_mm must be >= 0");
  if (normal_neighbors < 3) return fail(error, "normal_neighbors must be >= 3");
  return true;
}

}  // namespace conform
