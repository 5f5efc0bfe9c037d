#include "conform/registration/icp_options.h"

#include <cmath>
#include <utility>

namespace conform {

const char* to_string(IcpTermination termination) {
  switch (termination) {
    case IcpTermination::kConverged:
      return "converged";
    case IcpTermination::kMaxIterations:
      return "max_iterations";
    case IcpTermination::kTooFewCorrespondences:
      return "too_few_correspondences";
    case IcpTermination::kInsufficientOverlap:
      return "insufficient_overlap";
    case IcpTermination::kFailure:
      break;
  }
  return "failure";
}

const char* to_string(IcpMethod method) {
  switch (method) {
    case IcpMethod::kPointToPoint:
      return "point-to-point";
    case IcpMethod::kPointToPlane:
      return "point-to-plane";
    case IcpMethod::kPointToSurface:
      return "point-to-surface";
    case IcpMethod::kPlaneToPlane:
      return "plane-to-plane";
  }
  return "unknown";
}

const char* to_string(RobustKernel kernel) {
  switch (kernel) {
    case RobustKernel::kNone:
      return "none";
    case RobustKernel::kHuber:
      return "huber";
    case RobustKernel::kTukey:
      return "tukey";
  }
  return "unknown";
}

bool IcpOptions::IsValid(std::string* error) const {
  const auto fail = [error](std::string message) {
    if (error != nullptr) *error = std::move(message);
    return false;
  };
  if (!(max_correspondence_distance_mm > 0.0)) {
    return fail("max_correspondence_distance_mm = " + std::to_string(max_correspondence_distance_mm) +
                ": must be > 0 (infinity for no limit)");
  }
  if (!(overlap > 0.0 && overlap <= 1.0)) return fail("overlap = " + std::to_string(overlap) + ": must be in (0, 1]");
  if (!(overlap_lambda > 0.0) || !std::isfinite(overlap_lambda)) return fail("overlap_lambda must be finite and > 0");
  if (!(min_kernel_scale_mm > 0.0) || !std::isfinite(min_kernel_scale_mm)) {
    return fail("min_kernel_scale_mm must be finite and > 0");
  }
  if (!(start_std_mm >= 0.0) || !(start_std_rad >= 0.0)) return fail("start_std_mm and start_std_rad must be >= 0");
  if (!(convergence_std_fraction >= 0.0) || !std::isfinite(convergence_std_fraction)) {
    return fail("convergence_std_fraction must be finite and >= 0");
  }
  if (!(rotation_tolerance_rad >= 0.0) || !std::isfinite(rotation_tolerance_rad)) {
    return fail("rotation_tolerance_rad must be finite and >= 0");
  }
  if (!(translation_tolerance_mm >= 0.0) || !std::isfinite(translation_tolerance_mm)) {
    return fail("translation_tolerance_mm must be finite and >= 0");
  }
  if (!(gicp_epsilon > 0.0 && gicp_epsilon <= 1.0)) {
    return fail("gicp_epsilon = " + std::to_string(gicp_epsilon) + ": must be in (0, 1]");
  }
  if (max_iterations < 1) return fail("max_iterations = " + std::to_string(max_iterations) + ": must be >= 1");
  if (coarse_points > 0 && coarse_points < min_correspondences) {
    return fail("coarse_points must be 0 or at least min_correspondences");
  }
  if (min_correspondences < 3) return fail("min_correspondences must be >= 3");
  if (!(min_inlier_fraction >= 0.0 && min_inlier_fraction <= overlap)) {
    return fail("min_inlier_fraction = " + std::to_string(min_inlier_fraction) + ": must be in [0, overlap]");
  }
  if (free_dof.count() == 0) return fail("free_dof: every degree of freedom is locked; nothing to fit");
  if (!(free_tolerance_mm > 0.0) || !std::isfinite(free_tolerance_mm)) {
    return fail("free_tolerance_mm = " + std::to_string(free_tolerance_mm) + ": must be finite and > 0");
  }
  if (!(free_relative_eigenvalue >= 0.0 && free_relative_eigenvalue < 1.0)) {
    return fail("free_relative_eigenvalue = " + std::to_string(free_relative_eigenvalue) + ": must be in [0, 1)");
  }
  if (!(free_tolerance_rad > 0.0) || !std::isfinite(free_tolerance_rad)) {
    return fail("free_tolerance_rad = " + std::to_string(free_tolerance_rad) + ": must be finite and > 0");
  }
  return true;
}

}  // namespace conform
