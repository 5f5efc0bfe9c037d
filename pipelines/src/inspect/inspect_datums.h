#pragma once
// `conform inspect --datums A,B,C`: the 3-2-1 datum fit (as RPS alignment does). The primary datum is a plane: its
// least-squares plane is laid on its nominal plane (2 rotations, 1 translation). Then, with A's normal n:
//   B a plane:    turned about n and moved across n onto its nominal plane (1 rotation, 1 translation);
//     C a plane:    moved along the line A and B leave free (1 translation);
//     C a cylinder: its axis moved along that line onto the nominal axis (1 translation);
//   B a cylinder (its axis along n, a hole or boss square to A): its fitted axis moved across n onto the nominal axis
//     (2 translations);
//     C a plane:    the part turned about B's axis until C's normal, seen along n, is the nominal's (1 rotation);
//     C a cylinder: turned about B's axis until C's axis lies in the nominal direction from B's (1 rotation).
// What is fixed earlier is never moved later. Every other combination is refused.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad_faces.h"

namespace conform::detail {

// One datum: its nominal (a cylinder datum: its feature's merged faces, inspect_feature_groups.h) and the scan points
// assigned to it with their normals (in the frame the fit corrects).
struct DatumInput {
  std::size_t face_id = 0;
  CadFace nominal;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;
};

struct DatumFit {
  Eigen::Isometry3d T_datum_initial = Eigen::Isometry3d::Identity();  // p_datum = T * p (the correction)
  // Per datum, how far the fit moved it: a plane's fitted centroid along its nominal normal (signed), a cylinder's
  // fitted axis across A's normal (its length), a datum that only turns the part: its points' centroid (the length).
  std::vector<double> moved_mm;
};

// Throws conform::Error naming the datum and the supported combinations: a primary that is not a plane, a datum that
// is neither plane nor cylinder, too few points to fit it, a secondary plane parallel to the primary (within 10 deg),
// a secondary cylinder not square to the primary (its axis more than 10 deg from A's normal), a tertiary that does
// not fix what the first two leave free. 1 to 3 datums.
DatumFit fit_datums(const std::vector<DatumInput>& datums);

}  // namespace conform::detail
