// Fine ICP: conform (point-to-point and point-to-plane, OpenMP over the machine's cores) side by side with PCL 1.13's
// IterativeClosestPoint (point-to-point, SVD) and IterativeClosestPointWithNormals (point-to-plane, linear least
// squares), single-threaded as PCL runs them, on the same pairs: the box part (datasets/parts.h) meshed to ~10k, ~100k
// and ~1M vertices as the reference, a differently meshed copy with 0.02 mm noise as the scan, moved 3 degrees and
// 6 mm off the truth. Every run starts from the identity, with the same maximum pair distance (10 mm) and the same
// stopping rule (a step below 1e-6 rad and 1e-4 mm, at most 50 iterations; PCL at 1M points at most 30: see below).
// Times include building the search structure over the reference (both libraries do it per registration), not
// reading files or estimating normals (the parts carry exact normals). Wall-clock, best of 3 (1 at 1M points).
// Ratios > 1 mean PCL is slower. Errors are against the truth: the rotation angle and the translation length of
// T_est T_truth^-1.

// PCL's ICP templates, instantiated here, make GCC 12 report -Warray-bounds false positives inside Eigen's SSE loads
// of 3-float vectors; the warning is located in the intrinsics header, so the pragma must cover its first inclusion.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <pcl/registration/icp.h>

#include "bench_timer.h"
#include "conform/core/mesh.h"
#include "conform/datasets/parts.h"
#include "conform/registration/icp.h"
#pragma GCC diagnostic pop

namespace {

using conform::bench::best_seconds;
constexpr double kDeg = M_PI / 180.0;
constexpr double kMaxDistanceMm = 10.0;
constexpr int kMaxIterations = 50;
// PCL's point-to-point ICP at 1M points takes ~1.2 s an iteration here; 30 iterations keep its run under a minute.
constexpr int kPclMaxIterations1M = 30;

struct Pair {
  conform::Mesh reference, scan;  // scan in its own frame
  Eigen::Isometry3d truth;        // T_ref_scan
};

// The box part at the edge length that gives about n vertices, and a copy at 1.013 times that edge with noise.
Pair make_pair(std::size_t n) {
  conform::PartOptions probe;
  probe.edge_mm = 4.0;
  const double per_vertex = conform::surface_area(conform::box_part(probe)) / static_cast<double>(n);
  conform::PartOptions options;
  options.edge_mm = std::sqrt(per_vertex);
  Pair pair;
  pair.reference = conform::box_part(options);
  options.edge_mm *= 1.013;
  options.noise_mm = 0.02;
  options.seed = 5;
  conform::Mesh scan = conform::box_part(options);
  pair.truth = Eigen::Isometry3d::Identity();
  pair.truth.linear() = Eigen::AngleAxisd(3.0 * kDeg, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
  pair.truth.translation() = Eigen::Vector3d(4.0, -3.0, 3.0);  // 5.8 mm
  pair.scan = scan;
  const Eigen::Isometry3d T_scan_ref = pair.truth.inverse();
  for (std::size_t i = 0; i < scan.vertices.size(); ++i) {
    pair.scan.vertices[i] = T_scan_ref * scan.vertices[i];
    pair.scan.normals[i] = T_scan_ref.linear() * scan.normals[i];
  }
  return pair;
}

struct Row {
  std::string name;
  double seconds = 0.0;
  int iterations = 0;
  double rotation_deg = 0.0, translation_mm = 0.0;
};

void set_errors(Row& row, const Eigen::Isometry3d& est, const Eigen::Isometry3d& truth) {
  const Eigen::Isometry3d e = est * truth.inverse();
  row.rotation_deg = Eigen::AngleAxisd(e.linear()).angle() / kDeg;
  row.translation_mm = (est.translation() - truth.translation()).norm();
}

Row run_conform(const Pair& pair, conform::IcpMethod method, int repeats) {
  Row row;
  row.name = std::string("conform ") + conform::to_string(method);
  conform::IcpResult result;
  row.seconds = best_seconds(repeats, [&] {
    const conform::IcpReference reference(pair.reference);
    conform::IcpOptions options;
    options.method = method;
    options.max_correspondence_distance_mm = kMaxDistanceMm;
    options.max_iterations = kMaxIterations;
    result = conform::icp(pair.scan.vertices, reference, Eigen::Isometry3d::Identity(), options);
  });
  row.iterations = result.iterations;
  set_errors(row, result.T_ref_scan, pair.truth);
  return row;
}

template <typename Point>
typename pcl::PointCloud<Point>::Ptr pcl_cloud(const conform::Mesh& mesh) {
  typename pcl::PointCloud<Point>::Ptr cloud(new pcl::PointCloud<Point>);
  cloud->resize(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    (*cloud)[i].getVector3fMap() = mesh.vertices[i].cast<float>();
    if constexpr (std::is_same_v<Point, pcl::PointNormal>) {
      (*cloud)[i].getNormalVector3fMap() = mesh.normals[i].cast<float>();
    }
  }
  return cloud;
}

// The same stopping rule as conform's: translation step below 1e-4 mm (PCL compares its square), rotation step
// below 1e-6 rad (PCL compares the cosine); no stop on the fitness change.
template <typename Icp>
void configure(Icp& icp, int max_iterations) {
  icp.setMaxCorrespondenceDistance(kMaxDistanceMm);
  icp.setMaximumIterations(max_iterations);
  icp.setTransformationEpsilon(1e-8);
  icp.setTransformationRotationEpsilon(std::cos(1e-6));
  icp.setEuclideanFitnessEpsilon(-1.0);
}

template <typename Point, typename Icp>
Row run_pcl(const Pair& pair, const std::string& name, int max_iterations, int repeats) {
  Row row;
  row.name = name;
  const auto scan = pcl_cloud<Point>(pair.scan);
  const auto reference = pcl_cloud<Point>(pair.reference);
  Eigen::Matrix4f T = Eigen::Matrix4f::Identity();
  row.seconds = best_seconds(repeats, [&] {
    Icp icp;
    configure(icp, max_iterations);
    icp.setInputSource(scan);
    icp.setInputTarget(reference);
    pcl::PointCloud<Point> aligned;
    icp.align(aligned);
    T = icp.getFinalTransformation();
    row.iterations = icp.nr_iterations_;
  });
  set_errors(row, Eigen::Isometry3d(T.cast<double>()), pair.truth);
  return row;
}

// PCL keeps its iteration count protected; a subclass reads it.
template <typename Base>
struct Counted : Base {
  using Base::nr_iterations_;
};

void print(const Row& row, const Row* peer) {
  std::printf("  %-36s %9.3f s %4d it  rotation %.5f deg  translation %.5f mm", row.name.c_str(), row.seconds,
              row.iterations, row.rotation_deg, row.translation_mm);
  if (peer != nullptr) std::printf("   PCL/conform time %.1fx", peer->seconds / row.seconds);
  std::printf("\n");
}

}  // namespace

int main() {
  std::printf(
      "ICP benchmark: box part, start 3 deg / 5.8 mm off, max distance %.0f mm; conform on %d threads, PCL on 1\n",
      kMaxDistanceMm, omp_get_max_threads());
  for (std::size_t n : {10000u, 100000u, 1000000u}) {
    const Pair pair = make_pair(n);
    const bool big = n >= 1000000;
    const int repeats = big ? 1 : 3;
    const int pcl_iterations = big ? kPclMaxIterations1M : kMaxIterations;
    std::printf("\n%zu reference points, %zu scan points%s\n", pair.reference.vertices.size(),
                pair.scan.vertices.size(), big ? " (PCL capped at 30 iterations)" : "");
    const Row pcl_p2p = run_pcl<pcl::PointXYZ, Counted<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>>(
        pair, "PCL IterativeClosestPoint", pcl_iterations, repeats);
    const Row pcl_p2l =
        run_pcl<pcl::PointNormal, Counted<pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal>>>(
            pair, "PCL IterativeClosestPointWithNormals", pcl_iterations, repeats);
    const Row p2p = run_conform(pair, conform::IcpMethod::kPointToPoint, repeats);
    const Row p2l = run_conform(pair, conform::IcpMethod::kPointToPlane, repeats);
    print(pcl_p2p, nullptr);
    print(pcl_p2l, nullptr);
    print(p2p, &pcl_p2p);
    print(p2l, &pcl_p2l);
    std::printf("  conform point-to-plane against PCL IterativeClosestPoint: %.1fx\n", pcl_p2p.seconds / p2l.seconds);
  }
  return 0;
}
