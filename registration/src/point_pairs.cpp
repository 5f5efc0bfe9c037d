#include "conform/registration/point_pairs.h"

#include <cmath>
#include <string>

#include "conform/core/error.h"
#include "conform/registration/horn.h"

namespace conform {

PointPairsResult align_point_pairs(const std::vector<PointPair>& pairs) {
  if (pairs.size() < 3) {
    throw Error("point pairs: " + std::to_string(pairs.size()) +
                " given; at least 3 pairs (not on one line) are needed to fix a rigid transform");
  }
  std::vector<Eigen::Vector3d> scan, ref;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!pairs[i].scan.allFinite() || !pairs[i].reference.allFinite()) {
      throw Error("point pairs: pair " + std::to_string(i + 1) + " has a NaN or infinite coordinate");
    }
    scan.push_back(pairs[i].scan);
    ref.push_back(pairs[i].reference);
  }
  const HornResult horn = horn_transform(scan, ref);
  if (!horn.well_posed) {
    throw Error(
        "point pairs: the scan points lie on one line, so the rotation about it is not determined; give a "
        "pair off that line");
  }
  PointPairsResult result;
  result.T_ref_scan = horn.T_ref_scan;
  double sum = 0.0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const double r = (horn.T_ref_scan * scan[i] - ref[i]).norm();
    result.residuals_mm.push_back(r);
    sum += r * r;
    if (r > result.max_residual_mm) {
      result.max_residual_mm = r;
      result.worst_pair = i;
    }
  }
  result.rms_mm = std::sqrt(sum / static_cast<double>(pairs.size()));
  return result;
}

}  // namespace conform
