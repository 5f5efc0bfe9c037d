#pragma once
// The joint refinement of Subdivision-ICP's segment transforms (beyond the paper, which registers segments
// independently): one nonlinear least-squares problem (Ceres) over all segments' poses, with
//   data terms:    for every point p of segment k paired with the nominal surface at q with normal n,
//                  rho(n . (T_k p - q)), rho a Huber loss (the segment ICP's point-to-surface distance);
//   penalty terms: for shared overlap points c of neighbouring segments k and l (nominal contour points where both
//                  reach), w |T_k^-1 c - T_l^-1 c|^2: the two transforms' disagreement on where c is on the part;
//   damping terms: each segment's slide along the edge (its data's centroid) away from its own ICP's pose.
// Pairs are found again at the new poses between solves. T_k maps scan to nominal (T_nominal_scan).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/icp_reference.h"

namespace conform {

struct SicpJointOptions {
  // Weight of a neighbour's disagreement against the data: the penalty of a junction counts as much as this many
  // times the data terms of one segment when its disagreement equals a data residual. > 0.
  // Too strong and the segments cannot follow a stretch along a straight edge (which no segment sees on its own);
  // too weak and a segment's slide along a gently curved edge is left to noise. 0.01 from the seed sweep in
  // docs/measurements/sicp.md (plate, nose cone, harder oval and cut-out, seeds 2-4): 0.1 passed a corner segment's
  // error on through the overlaps, the harder cut-out's peak off the path 0.16 -> 0.64 mm.
  double weight = 0.01;
  // Weight of each segment's slide along the edge (from its own ICP's pose) against its data, the same scale as
  // `weight`: the data leave that slide nearly free on a gently curved edge, and without it the whole chain of
  // segments drifts along the edge together (1.4 mm on an open arc of the plate). 1e-4 stops that drift yet lets
  // a corner's hold pass along a straight edge (1e-2 kept wrong slides on the cut-out). >= 0.
  double damping = 1e-4;
  std::size_t points_per_overlap = 8;    // shared overlap points per junction (even along the overlap), >= 1
  std::size_t points_per_segment = 120;  // data points per segment, at most (even stride over the segment's ICP points)
  int rounds = 2;                        // pairing + solve rounds, >= 1
  int max_solver_iterations = 10;        // per solve
  double loss_scale_mm = 0.3;            // Huber scale of the data terms, > 0
  bool IsValid(std::string* error) const;
};

struct SicpJointReport {
  bool ran = false;
  bool usable = false;  // Ceres' solution is usable (converged or stopped with a better cost)
  int solver_iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  std::string termination;  // Ceres' last termination reason, or why it did not run
  // Largest disagreement |T_k^-1 c - T_l^-1 c| over the shared overlap points, before and after, mm.
  double max_disagreement_before_mm = 0.0;
  double max_disagreement_after_mm = 0.0;
};

// One segment's data: its points in the scan frame.
struct SicpJointSegment {
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3d along = Eigen::Vector3d::Zero();  // the edge's direction there (nominal frame); zero: no damping
};
// Shared overlap points (nominal frame) of neighbouring segments `left` and `right`.
struct SicpJointJunction {
  std::size_t left = 0, right = 0;
  std::vector<Eigen::Vector3d> points;
};

// T_nominal_scan: one per segment, refined in place. Throws conform::Error for invalid options or sizes that do not
// match; a reference without faces is used point-to-plane (its normals).
SicpJointReport refine_segments_jointly(const std::vector<SicpJointSegment>& segments,
                                        const std::vector<SicpJointJunction>& junctions, const IcpReference& nominal,
                                        double max_distance_mm, const SicpJointOptions& options,
                                        std::vector<Eigen::Isometry3d>& T_nominal_scan);

}  // namespace conform
