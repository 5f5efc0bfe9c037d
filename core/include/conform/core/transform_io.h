#pragma once
// Rigid transforms on disk: a 4x4 row-major text matrix, one row per line (the format CloudCompare reads and writes).

#include <string>

#include <Eigen/Geometry>

namespace conform {

// Throws conform::Error naming the file when it does not hold 16 numbers, the last row is not 0 0 0 1, or the
// upper-left 3x3 is not a rotation (orthonormal with determinant +1 within 1e-6). The rotation is re-orthonormalised.
Eigen::Isometry3d read_transform(const std::string& path);
// 17 significant digits, so that reading it back gives the same doubles. Atomic.
void write_transform(const std::string& path, const Eigen::Isometry3d& T);

}  // namespace conform
