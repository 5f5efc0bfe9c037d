#pragma once
// The pieces of FPFH global registration (coarse_fpfh.cpp), in conform's own code over core's kd-tree:
//   - statistical outlier removal (as PCL's StatisticalOutlierRemoval: a point's mean distance to its k nearest
//     neighbours against the mean and standard deviation of that over all points);
//   - Fast Point Feature Histograms (Rusu, Blodow & Beetz 2009, "Fast Point Feature Histograms (FPFH) for 3D
//     registration"): for each pair of a point and a neighbour within the radius, the Darboux frame u = n_s,
//     v = (p_t - p_s) x u / |.|, w = u x v (source s: the end whose normal makes the smaller angle with the line)
//     and its three angles alpha = v . n_t, phi = u . (p_t - p_s) / d, theta = atan2(w . n_t, u . n_t), each in 11
//     bins; a point's Simplified PFH (SPFH) sums its own pairs (each pair adds 100 / (neighbours - 1) to one bin of
//     each histogram), and its FPFH is the neighbours' SPFH weighted by 1 / d^2 (d: the neighbour's distance), each
//     histogram scaled to sum to 100. Where conform departs from the paper, as PCL does: the point's own SPFH is not
//     added (the weighted sum alone), and the weight is 1 / d^2 rather than 1 / d, which keeps its histograms
//     comparable with PCL's (docs/align.md, **Global registration**);
//   - nearest features in the 33-dimensional histogram space (exact, nanoflann), for the correspondences.
// Everything runs in float on points relative to a nearby origin (the caller's), as PCL's did.

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace conform::detail {

// Indices (ascending) of the points whose mean distance to their k nearest neighbours (themselves excluded) is at
// most mean + sigmas * std of that over all points (std with n - 1). All points when k <= 0 or there are at most k.
std::vector<std::size_t> statistical_inliers(const std::vector<Eigen::Vector3f>& points, int k, double sigmas);

constexpr int kFpfhBins = 11;  // per angle
using FpfhHistogram = std::array<float, 3 * kFpfhBins>;

// The three angles of the pair (p1, n1) -> (p2, n2) (unit normals) in the histogram's layout: theta in [-pi, pi],
// alpha and phi in [-1, 1] (PCL's order and ranges). False (angles zero) when the points coincide or the line
// between them is parallel to the source normal.
bool pair_angles(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                 const Eigen::Vector3f& n2, Eigen::Vector3f& angles);

// The FPFH of every point over the neighbours within `radius` (inclusive): bins of theta, then alpha, then phi. A
// point with a non-finite normal gets NaN in every bin (never matched); one without neighbours, zeros (as PCL's).
// Parallel over points; the same bits for any number of threads.
std::vector<FpfhHistogram> fpfh_histograms(const std::vector<Eigen::Vector3f>& points,
                                           const std::vector<Eigen::Vector3f>& normals, float radius);

// Exact nearest histograms (Euclidean) among a fixed set; rows with NaN are left out of the set. The set is read
// where it is: it must outlive the index.
class HistogramIndex {
 public:
  explicit HistogramIndex(const std::vector<FpfhHistogram>& histograms);
  ~HistogramIndex();
  HistogramIndex(const HistogramIndex&) = delete;
  HistogramIndex& operator=(const HistogramIndex&) = delete;
  // The min(k, size) nearest rows of the set (their indices in `histograms`) and squared distances, nearest first.
  void knn(const FpfhHistogram& query, int k, std::vector<std::size_t>& indices,
           std::vector<float>& sq_distances) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace conform::detail
