#pragma once
// Does the scan constrain all six degrees of freedom, and how well? The eigenvalues of the point-to-plane ICP normal
// matrix H = sum J_i^T J_i, J_i = [((q_i - c) x n_i) / L, n_i] (q_i scan points in the reference frame, n_i the
// reference normals they are paired with, c their centroid, L their RMS distance from c, so that rotation and
// translation are in comparable units), divided by the number of pairs. A direction whose eigenvalue is below a
// fraction of the largest moves the scan without changing any point-to-plane distance: a tube cannot fix translation
// along and rotation about its axis, a plane neither its in-plane translations nor the rotation about its normal.
// (Gelfand et al. 2003, "Geometrically stable sampling for the ICP algorithm"; Zhang et al. 2016.)
//
// How small is too small is a question of noise, not of a ratio: with N pairs and residual noise sigma, the
// least-squares pose has covariance sigma^2 (N H)^-1, so a direction of eigenvalue lambda is known to within
// sigma / sqrt(N lambda). A tube's axis (lambda ~1e-6 of the largest) is free; a ribbed plate's translation along
// its ribs (2.7e-4 of the largest) is known to micrometres from 100k points. analyze_constraint() holds a motion
// only when its predicted standard deviation exceeds a tolerance in mm or rad.

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
  // Its predicted standard deviation (analyze_constraint; 0 from analyze_degeneracy): along the translation, mm, or
  // about the rotation's axis, rad.
  double std_mm = 0.0;
  double std_rad = 0.0;
};

// One eigen-direction of H over the free degrees of freedom and how well the scan fixes it.
struct ConstraintDirection {
  // The motion, unit in the scaled coordinates: rotation (rad, about the centre) and translation (mm) per unit.
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double relative_eigenvalue = 0.0;
  double std_rad = 0.0;  // predicted standard deviation of its rotation part (the reported variance)
  double std_mm = 0.0;   // and of its translation part
  bool held = false;     // the noise's std beyond a tolerance: ICP holds it at the start
};

// The normalised point-to-plane normal matrix of a set of pairs, in coordinates (rotation x L [mm], translation [mm]).
struct PlaneNormalMatrix {
  Matrix6d H = Matrix6d::Zero();                     // sum J^T J / count
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // c, mm
  double length_scale_mm = 0.0;                      // L
  std::size_t count = 0;
  // sum r^2 J^T J / count (mm^2) when the residuals r are known: the middle of the sandwich (Huber-White) covariance
  // H^-1 M H^-1 / N, which sees residuals that are larger where the weak directions are measured. Zero: unknown.
  Matrix6d residual_moment = Matrix6d::Zero();
  // The cluster-robust middle (Liang & Zeger 1986): K/(K-1) sum_b g_b g_b^T / count (mm^2) over K spatial blocks of
  // the pairs, g_b = sum_{i in b} psi(r_i) J_i^T. Residuals that share a cause over a block (the bias of a reference
  // cloud's normals along a whole step edge) add up in g_b where the per-pair moment treats them as independent.
  // Zero: not computed (cluster_moment_of, once at the end of ICP).
  Matrix6d cluster_moment = Matrix6d::Zero();
  std::size_t clusters = 0;  // K
  // The robust fit's own bread: sum psi'(r_i) J^T J / count, psi the kernel's score (Huber: 1 within its scale, 0
  // beyond). The covariance of an M-estimate is bread^-1 middle bread^-1 / N; a pair the kernel saturates moves the
  // fit by a bounded amount whatever its position, so it adds no information. Zero: H (no kernel, or not known).
  Matrix6d bread = Matrix6d::Zero();
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

  // --- from analyze_constraint (zero from analyze_degeneracy) ---
  double noise_mm = 0.0;      // sigma, the residuals' robust standard deviation
  double tolerance_mm = 0.0;  // as given
  double tolerance_rad = 0.0;
  // sigma^2 (N H)^-1 over the free degrees of freedom, in (rx, ry, rz [rad], tx, ty, tz [mm]): rotations about the
  // reference frame's axes through `centre`, translations along them. Locked degrees of freedom have 0 rows and
  // columns; a direction with no constraint at all gets a huge (not infinite) variance.
  Matrix6d covariance = Matrix6d::Zero();
  Vector6d std = Vector6d::Zero();                    // sqrt of its diagonal: rad, rad, rad, mm, mm, mm
  std::vector<ConstraintDirection> eigen_directions;  // ascending eigenvalue, the free degrees of freedom only

  bool degenerate() const { return !directions.empty(); }
  // Smallest / largest eigenvalue (0 when there are none).
  double relative_smallest() const;
};

// The motions (translations, rotations about an axis through a point, with pitch) spanned by `basis` (6-vectors in
// the scaled coordinates of `report`: rotation x L about report.centre, translation), as analyze_constraint splits
// its held subspace; std_mm and std_rad from report.covariance.
std::vector<DegenerateDirection> motions_of(const std::vector<Vector6d>& basis, const DegeneracyReport& report,
                                            const Matrix6d& H);

// H from scan points q (reference frame) and the unit reference normals they are paired with.
PlaneNormalMatrix plane_normal_matrix(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& n);

// Adds the cluster-robust middle (PlaneNormalMatrix::cluster_moment) of `matrix`, made from the same q and n, over
// `clusters` contiguous runs of the pairs (spatially ordered pairs: compact patches), psi the pairs' robust scores
// (weighted residuals along n, mm). Fewer than 2 runs: nothing added.
void add_cluster_moment(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& n,
                        const std::vector<double>& psi, std::size_t clusters, PlaneNormalMatrix& matrix);

// The eigen-analysis of H over the free degrees of freedom, with the degenerate subspace split into pure
// translations and rotations (axis through the point it passes closest to the centroid).
DegeneracyReport analyze_degeneracy(const PlaneNormalMatrix& matrix, double threshold, const FreeDof& free_dof = {});

// The same split, with the degenerate subspace chosen by predicted standard deviation: an eigen-direction u is held
// when sigma / sqrt(N lambda) (N = matrix.count, sigma = noise_mm > 0) moves it more than max(tolerance_mm,
// start_std_mm) along, or max(tolerance_rad, start_std_rad) about, some axis (loose, and the start known better than
// the data would give it), and its eigenvalue is below 1e-2 of the largest (a direction fixed within ten times
// the best one's std is never held: holding it cannot beat the data). The covariance is taken on the robust fit's
// bread B (matrix.bread; H when zero): along B's eigen-directions v (eigenvalue mu) the larger of sigma^2 / (N mu) and
// the sandwich estimate v^T M v / (N mu^2) (M = matrix.residual_moment), A = V diag(variances) V^T;
// with a cluster moment C (matrix.clusters > 0) the covariance is A + (S - A)_+, S = B^-1 C B^-1 / N the
// cluster-robust sandwich over the free degrees of freedom and (.)_+ the positive part of a symmetric matrix: the
// least change of A that bounds both A and S from above, so every direction's std is at least either's. start_std 0
// (the default here): the start is exact, every loose direction is held. Directions below min_relative of the largest
// eigenvalue are held whatever their std: they are fixed only by second-order effects (a mesh's facets, the normals'
// estimate) whose errors are systematic and do not average out over the N points the std assumes independent.
DegeneracyReport analyze_constraint(const PlaneNormalMatrix& matrix, double noise_mm, double tolerance_mm,
                                    double tolerance_rad, const FreeDof& free_dof = {}, double min_relative = 0.0,
                                    double start_std_mm = 0.0, double start_std_rad = 0.0);

// How far the estimated pose may move the scan: the largest over `points` (reference frame, mm) of the predicted
// displacement std sqrt(sum_i var_i |r_i x (p - c) + t_i|^2), over the eigen-directions i that were estimated (not
// held) by analyze_constraint, r_i and t_i a direction's rotation (rad) and translation (mm) per unit, var_i its
// variance, c the report's centre: the root of the trace of the displacement's covariance where the directions are
// independent, an upper bound of its largest directional std. One figure for "how well does the scan fix the pose",
// in mm at the part, whatever the part's size (a fixed angle asks 100 times more of a 10 m part than of a 10 cm
// one). Held motions are reported apart (directions). 0 for no points or a report without eigen-directions.
double largest_displacement_std_mm(const DegeneracyReport& report, const std::vector<Eigen::Vector3d>& points);

}  // namespace conform
