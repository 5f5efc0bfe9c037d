#pragma once
// `conform pose-error`: how far apart two rigid transforms on disk are (evaluation/pose_error.h), for accuracy
// scripts comparing an estimate with the truth or two runs with each other.

#include <string>

#include <Eigen/Geometry>

#include "conform/evaluation/pose_error.h"

namespace conform {

struct PoseErrorOptions {
  std::string path_a;  // 4x4 row-major text matrix (core/transform_io.h)
  std::string path_b;
  double mm_per_unit = 1.0;  // millimetres per unit of the translations (1000 for transforms in metres)
};

struct PoseErrorResult {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();  // as read, translation in mm
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  PoseError error;
};

// Throws conform::Error naming the file that cannot be read or is not a rigid transform, or the bad unit factor.
PoseErrorResult run_pose_error(const PoseErrorOptions& options);

}  // namespace conform
