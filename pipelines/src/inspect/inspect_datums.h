#pragma once
// `conform inspect --datums A,B,C`: the 3-2-1 datum fit (as RPS alignment does). Planes only: the primary datum's
// least-squares plane is laid on its nominal plane (2 rotations, 1 translation), the secondary's turned about the
// primary's normal and moved across it onto its nominal (1 rotation, 1 translation), the tertiary moved along the line
// both leave free (1 translation). What is fixed earlier is never moved later.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad_faces.h"

namespace conform::detail {

// One datum: its nominal face and the scan points assigned to it (in the frame the fit corrects).
struct DatumInput {
  std::size_t face_id = 0;
  CadFace nominal;
  std::vector<Eigen::Vector3d> points;
};

struct DatumFit {
  Eigen::Isometry3d T_datum_initial = Eigen::Isometry3d::Identity();  // p_datum = T * p (the correction)
  std::vector<double> moved_mm;  // per datum, how far its fitted plane's centroid moved along its nominal normal
};

// Throws conform::Error naming the datum: not a plane, fewer than 3 points or on a line, a secondary parallel to the
// primary (within 10 deg), a tertiary that does not fix the line the first two leave free (its normal within 80 deg
// of perpendicular to it). 1 to 3 datums.
DatumFit fit_datums(const std::vector<DatumInput>& datums);

}  // namespace conform::detail
