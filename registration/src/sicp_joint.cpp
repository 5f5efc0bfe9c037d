#include "conform/registration/sicp_joint.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "conform/core/error.h"
#include "conform/registration/sicp_pairs.h"

namespace conform {
namespace {

// A pose change D = (rotation vector w, translation v) applied on the left of the current T_nominal_scan.
constexpr int kPose = 6;

// n . (D p - q) for p already mapped by the current transform.
struct DataCost {
  Eigen::Vector3d p, q, n;
  template <typename T>
  bool operator()(const T* const d, T* residual) const {
    const T point[3] = {T(p.x()), T(p.y()), T(p.z())};
    T moved[3];
    ceres::AngleAxisRotatePoint(d, point, moved);
    residual[0] = T(n.x()) * (moved[0] + d[3] - T(q.x())) + T(n.y()) * (moved[1] + d[4] - T(q.y())) +
                  T(n.z()) * (moved[2] + d[5] - T(q.z()));
    return true;
  }
};

// The nominal point c mapped to the scan by either segment's new transform, (D_k T_k)^-1 c = T_k^-1 D_k^-1 c; the
// residual is the difference, scaled by sqrt(weight).
struct AgreementCost {
  Eigen::Vector3d c;
  Eigen::Matrix3d A_left, A_right;  // rotations of the current T^-1
  Eigen::Vector3d a_left, a_right;  // translations
  double scale;

  template <typename T>
  static void undo(const T* d, const Eigen::Vector3d& c, T* out) {  // D^-1 c = R(-w) (c - v)
    const T w[3] = {-d[0], -d[1], -d[2]};
    const T shifted[3] = {T(c.x()) - d[3], T(c.y()) - d[4], T(c.z()) - d[5]};
    ceres::AngleAxisRotatePoint(w, shifted, out);
  }
  template <typename T>
  bool operator()(const T* const left, const T* const right, T* residual) const {
    T l[3], r[3];
    undo(left, c, l);
    undo(right, c, r);
    for (int i = 0; i < 3; ++i) {
      T li = T(a_left(i)), ri = T(a_right(i));
      for (int j = 0; j < 3; ++j) {
        li += T(A_left(i, j)) * l[j];
        ri += T(A_right(i, j)) * r[j];
      }
      residual[i] = T(scale) * (li - ri);
    }
    return true;
  }
};

// Damping of a segment's pose change along the edge: the displacement of its data's centroid c along the edge's
// direction t, t . (D c - c), scaled by sqrt(weight). The data leave that slide free on a gently curved edge, where
// the faceted nominal surface pulls at it and the overlap penalties pass it on: without damping the whole chain
// drifts along the edge together.
struct DampingCost {
  Eigen::Vector3d c, t;
  double scale;
  template <typename T>
  bool operator()(const T* const d, T* residual) const {
    const T point[3] = {T(c.x()), T(c.y()), T(c.z())};
    T moved[3];
    ceres::AngleAxisRotatePoint(d, point, moved);
    residual[0] = T(0.0);
    for (int i = 0; i < 3; ++i) residual[0] += T(scale * t(i)) * (moved[i] + d[3 + i] - point[i]);
    return true;
  }
};

Eigen::Isometry3d pose_of(const double* d) {
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w(d[0], d[1], d[2]);
  if (w.norm() > 0.0) D.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  D.translation() = Eigen::Vector3d(d[3], d[4], d[5]);
  return D;
}

double max_disagreement(const std::vector<SicpJointJunction>& junctions, const std::vector<Eigen::Isometry3d>& T) {
  double worst = 0.0;
  for (const SicpJointJunction& j : junctions) {
    const Eigen::Isometry3d L = T[j.left].inverse(), R = T[j.right].inverse();
    for (const Eigen::Vector3d& c : j.points) worst = std::max(worst, (L * c - R * c).norm());
  }
  return worst;
}

// One pairing + solve round; returns the solver's summary.
ceres::Solver::Summary solve_round(const std::vector<SicpJointSegment>& segments,
                                   const std::vector<SicpJointJunction>& junctions, const IcpReference& nominal,
                                   double max_distance_mm, const SicpJointOptions& o,
                                   std::vector<Eigen::Isometry3d>& T) {
  std::vector<double> deltas(kPose * segments.size(), 0.0);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::HuberLoss loss(o.loss_scale_mm);
  std::size_t data_terms = 0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    double* d = &deltas[kPose * k];
    problem.AddParameterBlock(d, kPose);
    const std::vector<Eigen::Vector3d>& points = segments[k].points;
    std::vector<ReferencePoint> pairs(points.size());
    const auto n = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(static) if (n > 256)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      pairs[static_cast<std::size_t>(i)] =
          closest_on_reference(nominal, T[k] * points[static_cast<std::size_t>(i)], max_distance_mm);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!pairs[i].found) continue;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DataCost, 1, kPose>(
                                   new DataCost{T[k] * points[i], pairs[i].point, pairs[i].normal}),
                               &loss, d);
      ++data_terms;
    }
  }
  // A junction's penalty weighs like `weight` segments' data: per residual, weight * (data terms per segment) /
  // (points per junction).
  const double per_segment =
      static_cast<double>(data_terms) / static_cast<double>(std::max<std::size_t>(1, segments.size()));
  for (const SicpJointJunction& j : junctions) {
    if (j.points.empty() || j.left == j.right) continue;
    const double scale = std::sqrt(o.weight * std::max(1.0, per_segment) / static_cast<double>(j.points.size()));
    const Eigen::Isometry3d L = T[j.left].inverse(), R = T[j.right].inverse();
    for (const Eigen::Vector3d& c : j.points) {
      auto* cost = new AgreementCost{c, L.linear(), R.linear(), L.translation(), R.translation(), scale};
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AgreementCost, 3, kPose, kPose>(cost), nullptr,
                               &deltas[kPose * j.left], &deltas[kPose * j.right]);
    }
  }
  if (o.damping > 0.0) {
    const double scale = std::sqrt(o.damping * std::max(1.0, per_segment));
    for (std::size_t k = 0; k < segments.size(); ++k) {
      if (segments[k].points.empty() || segments[k].along.norm() < 0.5) continue;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& p : segments[k].points) centroid += T[k] * p;
      centroid /= static_cast<double>(segments[k].points.size());
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DampingCost, 1, kPose>(
                                   new DampingCost{centroid, segments[k].along.normalized(), scale}),
                               nullptr, &deltas[kPose * k]);
    }
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;  // block-tridiagonal (a ring when closed)
  options.max_num_iterations = o.max_solver_iterations;
  options.num_threads = 1;  // the same bytes whatever the machine
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (summary.IsSolutionUsable()) {
    for (std::size_t k = 0; k < segments.size(); ++k) T[k] = pose_of(&deltas[kPose * k]) * T[k];
  }
  return summary;
}

}  // namespace

bool SicpJointOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(weight) || weight <= 0.0)
    why = "joint weight must be > 0";
  else if (points_per_overlap < 1)
    why = "points per overlap must be >= 1";
  else if (points_per_segment < 1)
    why = "joint points per segment must be >= 1";
  else if (rounds < 1)
    why = "joint rounds must be >= 1";
  else if (max_solver_iterations < 1)
    why = "joint solver iterations must be >= 1";
  else if (!std::isfinite(damping) || damping < 0.0)
    why = "joint damping must be >= 0";
  else if (!std::isfinite(loss_scale_mm) || loss_scale_mm <= 0.0)
    why = "joint loss scale must be > 0 mm";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

SicpJointReport refine_segments_jointly(const std::vector<SicpJointSegment>& segments,
                                        const std::vector<SicpJointJunction>& junctions, const IcpReference& nominal,
                                        double max_distance_mm, const SicpJointOptions& options,
                                        std::vector<Eigen::Isometry3d>& T_nominal_scan) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("S-ICP joint refinement: " + why);
  if (T_nominal_scan.size() != segments.size()) throw Error("S-ICP joint refinement: one transform per segment");
  for (const SicpJointJunction& j : junctions) {
    if (j.left >= segments.size() || j.right >= segments.size())
      throw Error("S-ICP joint refinement: a junction refers to a segment that does not exist");
  }
  SicpJointReport report;
  report.max_disagreement_before_mm = max_disagreement(junctions, T_nominal_scan);
  report.ran = true;
  report.usable = true;
  for (int round = 0; round < options.rounds; ++round) {
    const ceres::Solver::Summary s =
        solve_round(segments, junctions, nominal, max_distance_mm, options, T_nominal_scan);
    if (round == 0) report.initial_cost = s.initial_cost;
    report.final_cost = s.final_cost;
    report.solver_iterations += static_cast<int>(s.iterations.size());
    report.termination = ceres::TerminationTypeToString(s.termination_type);
    report.usable = report.usable && s.IsSolutionUsable();
    if (!s.IsSolutionUsable()) break;
  }
  report.max_disagreement_after_mm = max_disagreement(junctions, T_nominal_scan);
  return report;
}

}  // namespace conform
