// Nearest-neighbour search: PCL's KdTreeFLANN against nanoflann (leaf sizes 10 and 20) and conform::KdTree (nanoflann
// with points stored in leaf order and (distance, index) ordering), single-threaded, best of 3. Clouds: (a) uniform in
// a 500 mm cube, (b) a scanner-like tube surface (radius 100 mm, length 500 mm, 10 um Gaussian noise), 100k and 1M
// points each; 100k queries per row (uniform: fresh points in the cube; tube: fresh points on the tube). The radius is
// the median distance of the 20th neighbour, so a radius query returns ~20 points. Ratios > 1 mean the peer (PCL) is
// slower. Afterwards: conform::estimate_normals (k = 16) on the 1M-point tube with 1 and 2 OpenMP threads.

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <pcl/kdtree/kdtree_flann.h>
#include <nanoflann.hpp>

#include "bench_timer.h"
#include "conform/core/constants.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/normals.h"

using conform::kPi;

namespace {

using conform::bench::best_cpu_seconds;
using conform::bench::best_seconds;
using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

constexpr int kRepeats = 3;
constexpr std::size_t kQueries = 100000;

PclCloud uniform_cloud(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 500.0f);
  PclCloud cloud;
  cloud.resize(n);
  for (auto& p : cloud) p = pcl::PointXYZ(u(rng), u(rng), u(rng));
  return cloud;
}

PclCloud tube_cloud(std::size_t n, std::uint32_t seed) {
  constexpr double kRadius = 100.0, kLength = 500.0, kNoise = 0.010;  // mm
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), along(0.0, kLength);
  std::normal_distribution<double> noise(0.0, kNoise);
  PclCloud cloud;
  cloud.resize(n);
  for (auto& p : cloud) {
    const double a = angle(rng), r = kRadius + noise(rng);
    p = pcl::PointXYZ(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                      static_cast<float>(along(rng)));
  }
  return cloud;
}

// nanoflann reads points through this adaptor over a flat float array (the layout conform::KdTree keeps too).
struct FlatCloud {
  std::vector<float> xyz;
  std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return xyz[3 * i + dim]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox& /*bbox*/) const {
    return false;
  }
};
using NanoTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FlatCloud>, FlatCloud, 3, std::uint32_t>;

// One implementation under test: build once, then run the three kinds of query over all queries.
// Each query call returns a checksum (sum of indices) so that the work cannot be optimised away and the
// implementations can be compared.
struct Timings {
  double build = 0, k1 = 0, k10 = 0, radius = 0;
  std::uint64_t sum_k1 = 0, sum_k10 = 0, found_radius = 0;
};

template <typename Build, typename Knn, typename Radius>
Timings measure(const PclCloud& queries, float radius, Build&& build, Knn&& knn, Radius&& radius_search) {
  Timings t;
  t.build = best_cpu_seconds(kRepeats, build);
  t.k1 = best_cpu_seconds(kRepeats, [&] {
    t.sum_k1 = 0;
    for (const auto& q : queries) t.sum_k1 += knn(q, 1);
  });
  t.k10 = best_cpu_seconds(kRepeats, [&] {
    t.sum_k10 = 0;
    for (const auto& q : queries) t.sum_k10 += knn(q, 10);
  });
  t.radius = best_cpu_seconds(kRepeats, [&] {
    t.found_radius = 0;
    for (const auto& q : queries) t.found_radius += radius_search(q, radius);
  });
  return t;
}

Timings measure_pcl(const PclCloud& cloud, const PclCloud& queries, float radius) {
  const auto shared = std::make_shared<const PclCloud>(cloud);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  std::vector<int> idx;
  std::vector<float> d2;
  return measure(
      queries, radius, [&] { tree.setInputCloud(shared); },
      [&](const pcl::PointXYZ& q, int k) {
        tree.nearestKSearch(q, k, idx, d2);
        std::uint64_t s = 0;
        for (int i : idx) s += static_cast<std::uint64_t>(i);
        return s;
      },
      [&](const pcl::PointXYZ& q, float r) {
        return static_cast<std::uint64_t>(tree.radiusSearch(q, static_cast<double>(r), idx, d2));
      });
}

Timings measure_nanoflann(const PclCloud& cloud, const PclCloud& queries, float radius, std::size_t leaf) {
  FlatCloud flat;
  std::unique_ptr<NanoTree> tree;
  std::vector<std::uint32_t> idx(10);
  std::vector<float> d2(10);
  std::vector<std::pair<std::uint32_t, float>> matches;
  return measure(
      queries, radius,
      [&] {
        // The copy into the flat array is part of the build, as in KdTreeFLANN::setInputCloud.
        flat.xyz.clear();
        flat.xyz.reserve(3 * cloud.size());
        for (const auto& p : cloud) flat.xyz.insert(flat.xyz.end(), {p.x, p.y, p.z});
        tree = std::make_unique<NanoTree>(3, flat, nanoflann::KDTreeSingleIndexAdaptorParams(leaf));
      },
      [&](const pcl::PointXYZ& q, int k) {
        const std::size_t found = tree->knnSearch(q.data, static_cast<std::size_t>(k), idx.data(), d2.data());
        std::uint64_t s = 0;
        for (std::size_t i = 0; i < found; ++i) s += idx[i];
        return s;
      },
      [&](const pcl::PointXYZ& q, float r) {
        return static_cast<std::uint64_t>(tree->radiusSearch(q.data, r * r, matches, nanoflann::SearchParams()));
      });
}

Timings measure_conform(const PclCloud& cloud, const PclCloud& queries, float radius) {
  std::unique_ptr<conform::KdTree> tree;
  std::vector<int> idx;
  std::vector<float> d2;
  return measure(
      queries, radius, [&] { tree = std::make_unique<conform::KdTree>(cloud); },
      [&](const pcl::PointXYZ& q, int k) {
        tree->knn(q.getVector3fMap(), k, idx, d2);
        std::uint64_t s = 0;
        for (int i : idx) s += static_cast<std::uint64_t>(i);
        return s;
      },
      [&](const pcl::PointXYZ& q, float r) {
        tree->radius(q.getVector3fMap(), r, idx, d2);
        return static_cast<std::uint64_t>(idx.size());
      });
}

// Median distance to the 20th neighbour over 1000 queries (widened a little, so that the median's own point does not
// lie exactly on the sphere).
float radius_for_20_neighbours(const PclCloud& cloud, const PclCloud& queries) {
  const conform::KdTree tree(cloud);
  std::vector<int> idx;
  std::vector<float> d2;
  std::vector<float> r;
  for (std::size_t i = 0; i < 1000; ++i) {
    tree.knn(queries[i].getVector3fMap(), 20, idx, d2);
    r.push_back(std::sqrt(d2.back()));
  }
  std::nth_element(r.begin(), r.begin() + 500, r.end());
  return 1.0001f * r[500];
}

void print_row(const char* op, double pcl, double n10, double n20, double conform) {
  std::printf("  %-8s %9.1f %9.1f %9.1f %9.1f   %6.2f %6.2f %6.2f\n", op, 1e3 * pcl, 1e3 * n10, 1e3 * n20,
              1e3 * conform, pcl / n10, pcl / n20, pcl / conform);
}

void run_case(const char* name, const PclCloud& cloud, const PclCloud& queries) {
  const float radius = radius_for_20_neighbours(cloud, queries);
  const Timings pcl = measure_pcl(cloud, queries, radius);
  const Timings n10 = measure_nanoflann(cloud, queries, radius, 10);
  const Timings n20 = measure_nanoflann(cloud, queries, radius, 20);
  const Timings conform = measure_conform(cloud, queries, radius);
  std::printf("%s, %zu points, %zu queries, radius %.3f mm (mean %.1f neighbours)\n", name, cloud.size(),
              queries.size(), static_cast<double>(radius),
              static_cast<double>(conform.found_radius) / static_cast<double>(queries.size()));
  std::printf("  %-8s %9s %9s %9s %9s   %6s %6s %6s\n", "[ms]", "PCL", "nano10", "nano20", "conform", "P/n10", "P/n20",
              "P/conf");
  print_row("build", pcl.build, n10.build, n20.build, conform.build);
  print_row("k=1", pcl.k1, n10.k1, n20.k1, conform.k1);
  print_row("k=10", pcl.k10, n10.k10, n20.k10, conform.k10);
  print_row("radius", pcl.radius, n10.radius, n20.radius, conform.radius);
  // Same k nearest everywhere (random float clouds practically never have ties). Radius hits can differ by the rare
  // point whose squared distance rounds to exactly radius^2: conform's radius is inclusive, the others' exclusive.
  const bool same_knn = pcl.sum_k1 == n10.sum_k1 && pcl.sum_k1 == conform.sum_k1 && pcl.sum_k10 == n10.sum_k10 &&
                        pcl.sum_k10 == conform.sum_k10;
  std::printf("  same k nearest: %s; radius hits: PCL %llu, nanoflann %llu, conform %llu\n\n", same_knn ? "yes" : "NO",
              static_cast<unsigned long long>(pcl.found_radius), static_cast<unsigned long long>(n10.found_radius),
              static_cast<unsigned long long>(conform.found_radius));
}

// The 1-minute load average (Linux), printed beside wall-clock figures: on a shared machine a second thread only helps
// when a core is free.
double load_average() {
  double load = -1.0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = -1.0;
    std::fclose(f);
  }
  return load;
}

void run_normals() {
  conform::Cloud cloud;
  cloud.points = tube_cloud(1000000, 7);
  conform::NormalOptions options;
  options.orientation = conform::NormalOrientation::kAwayFromAxis;
  double seconds[2] = {0, 0};
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    seconds[threads - 1] = best_seconds(kRepeats, [&] { (void)conform::estimate_normals(cloud, options); });
  }
  std::printf(
      "estimate_normals, tube, %zu points in random order, k = %d, wall-clock best of %d: 1 thread %.2f s (%.0f k "
      "points/s), 2 threads %.2f s (%.0f k points/s), speed-up %.2f (load average %.1f on %d cores)\n",
      cloud.size(), options.k, kRepeats, seconds[0], 1e-3 * static_cast<double>(cloud.size()) / seconds[0], seconds[1],
      1e-3 * static_cast<double>(cloud.size()) / seconds[1], seconds[0] / seconds[1], load_average(),
      omp_get_num_procs());
}

}  // namespace

int main() {
  std::printf("nearest-neighbour search, single thread, best of %d; thread CPU time in ms for all queries\n\n",
              kRepeats);
  for (std::size_t n : {std::size_t{100000}, std::size_t{1000000}}) {
    run_case("uniform", uniform_cloud(n, 1), uniform_cloud(kQueries, 2));
    run_case("tube", tube_cloud(n, 3), tube_cloud(kQueries, 4));
  }
  run_normals();
  return 0;
}
