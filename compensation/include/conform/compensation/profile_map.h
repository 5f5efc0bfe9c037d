#pragma once
// The map from a designed point (Tx, Ty) on the straight, flat profile to the deformed profile (Chen et al., LNG
// profiles): find t with s(t) = Ty on the edge curve (Eq. 7), then P' = C(t) + Tx V1(t) (Eq. 4-6), where V1 is the
// unit direction across the web, perpendicular to the edge:
//
//   global  V1 = normalize(Z x C'(t)) with one web normal Z for the whole profile (the paper);
//   local   beyond the paper, for twist: V1 is the part perpendicular to C'(t) of the vector from C(t) to the foot of
//           the perpendicular on the second measured edge (the profile's other edge, on the +Tx side), so that the
//           web direction turns with the profile.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/compensation/profile_edge.h"

namespace conform {

struct ProfileMappedPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // P', mm
  Eigen::Vector3d across = Eigen::Vector3d::UnitY();   // V1, unit
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();  // V(t) of the edge (Eq. 4), unit
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // the web's normal there, V x V1 (the tool axis), unit
  double t = 0.0;                                      // edge parameter with s(t) = Ty
  double arc_length_residual_mm = 0.0;                 // s(t) - Ty
  double local_width_mm = 0.0;                         // local map: the measured web width at t; 0 otherwise
};

class ProfileMap {
 public:
  // Global web normal Z (need not be unit; throws conform::Error when it is zero, not finite, or parallel to the edge).
  ProfileMap(ProfileEdgeCurve edge, const Eigen::Vector3d& web_normal, double tolerance_mm = 1e-8);
  // Local web direction from a second edge curve.
  ProfileMap(ProfileEdgeCurve edge, ProfileEdgeCurve second_edge, double tolerance_mm = 1e-8);

  bool local() const { return local_; }
  const ProfileEdgeCurve& edge() const { return edge_; }
  const Eigen::Vector3d& web_normal() const { return z_; }

  // Throws conform::Error when Ty lies outside [0, edge length] or V1 degenerates (the edge's tangent parallel to Z).
  ProfileMappedPoint map(double tx_mm, double ty_mm) const;

 private:
  Eigen::Vector3d across_local(const Eigen::Vector3d& p, const Eigen::Vector3d& tangent, double ty_mm,
                               double* width_mm) const;

  ProfileEdgeCurve edge_;
  ProfileEdgeCurve second_;
  Eigen::Vector3d z_ = Eigen::Vector3d::UnitZ();
  bool local_ = false;
  double tolerance_mm_ = 1e-8;
};

struct ProfileWebNormal {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, oriented with z >= 0
  double flatness_ratio = 0.0;  // sqrt(middle / smallest eigenvalue of the scatter): how well the plane is defined
};

// The web normal as the normal of the least-squares plane of the points (the edge points, and the second edge's),
// oriented towards +z. Throws conform::Error when the plane is undetermined: fewer than 3 points, or points so
// nearly on a line (flatness_ratio < min_flatness_ratio) that the normal is noise; the message says to give the web
// normal or a second edge.
ProfileWebNormal fit_profile_web_normal(const std::vector<Eigen::Vector3d>& points, double min_flatness_ratio = 10.0);

}  // namespace conform
