#pragma once
// Does the scan constrain all six degrees of freedom? The eigenvalues of the point-to-plane ICP normal matrix
// H = sum J_i^T J_i, J_i = [((q_i - c) x n_i) / L, n_i] (q_i scan points in the reference frame, n_i the reference
// normals they are paired with, c their centroid, L their RMS distance from c, so that rotation and translation are
// in comparable units), divided by the number of pairs. A direction whose eigenvalue is below a fraction of the
// largest moves the scan without changing any point-to-plane distance: a tube cannot fix translation along and
// rotation about its axis, a plane neither its in-plane translations nor the rotation about its normal.
// (Gelfand et al. 2003, "Geometrically stable sampling for the ICP algorithm"; Zhang et al. 2016.)

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/registration/icp_options.h"

namespace conform {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

enum class MotionKind { kTranslation, kRotation };

// A motion of the scan that the point-to-plane distances do not see. Reference frame.
struct DegenerateDirection {
  MotionKind kind = MotionKind::kTranslation;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit: the translation's direction, or the rotation's axis
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       // rotation: the point of its axis closest to the centroid, mm
  double pitch_mm_per_rad = 0.0;                         // rotation: the translation along the axis that goes with it
  double relative_eigenvalue = 0.0;                      // its eigenvalue / the largest one
};

// The normalised point-to-plane normal matrix of a set of pairs, in coordinates (rotation x L [mm], translation [mm]).
struct PlaneNormalMatrix {
  Matrix6d H = Matrix6d::Zero();                     // sum J^T J / count
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // c, mm
  double length_scale_mm = 0.0;                      // L
  std::size_t count = 0;
};

struct DegeneracyReport {
  // Eigenvalues of H restricted to the free degrees of freedom, ascending (6 when all are free); dimensionless: a
  // plane's normal translation has 1, a closed sphere's three translations 1/3 each.
  Eigen::VectorXd eigenvalues;
  double threshold = 0.0;  // relative, as given
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double length_scale_mm = 0.0;
  std::vector<DegenerateDirection> directions;  // translations first, then rotations; empty when fully constrained
  // Unit eigenvectors (6-vectors in the scaled coordinates) of the degenerate subspace, what ICP holds fixed.
  std::vector<Vector6d> degenerate_basis;

  bool degenerate() const { return !directions.empty(); }
  // Smallest / largest eigenvalue (0 when there are none).
  double relative_smallest() const;
};

// H from scan points q (reference frame) and the unit reference normals they are paired with.
PlaneNormalMatrix plane_normal_matrix(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& n);

// The eigen-analysis of H over the free degrees of freedom, with the degenerate subspace split into pure
// translations and rotations (axis through the point it passes closest to the centroid).
DegeneracyReport analyze_degeneracy(const PlaneNormalMatrix& matrix, double threshold, const FreeDof& free_dof = {});

}  // namespace conform
