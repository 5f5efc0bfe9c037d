#include "conform/datasets/profile.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {
namespace {

// Independent streams, so that turning one effect on or off leaves the others' numbers alone.
constexpr std::uint64_t kEdgeNoiseStream = 1;
constexpr std::uint64_t kSecondEdgeNoiseStream = 2;
constexpr std::uint64_t kDropoutStream = 3;
constexpr std::uint64_t kOutlierStream = 4;

// Moves `count` distinct samples (never the first or the last) across the edge (y) or along the web normal (z).
void add_outliers(const ProfileScanOptions& o, std::vector<Eigen::Vector3d>* edge, std::vector<std::size_t>* which) {
  if (o.outliers <= 0 || edge->size() < 3) return;
  Random random(o.seed, kOutlierStream);
  std::vector<bool> moved(edge->size(), false);
  const std::size_t inner = edge->size() - 2;
  const std::size_t count = std::min(static_cast<std::size_t>(o.outliers), inner);
  while (which->size() < count) {
    const std::size_t i = 1 + std::min(inner - 1, static_cast<std::size_t>(random.uniform() * static_cast<double>(inner)));
    if (moved[i]) continue;
    moved[i] = true;
    const double sign = random.uniform() < 0.5 ? -1.0 : 1.0;
    (*edge)[i][random.uniform() < 0.5 ? 1 : 2] += sign * o.outlier_mm;
    which->push_back(i);
  }
  std::sort(which->begin(), which->end());
}

std::vector<Eigen::Vector3d> sample_edge(const ProfileDeformation& shape, const ProfileScanOptions& o, double tx_mm,
                                         const std::vector<bool>& keep, Random* noise) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(keep.size());
  for (std::size_t j = 0; j < keep.size(); ++j) {
    const double s = std::min(static_cast<double>(j) * o.spacing_mm, o.deformation.length_mm);
    Eigen::Vector3d p = shape.map(tx_mm, s);
    // Drawn for every sample, kept or not, so that the dropouts do not shift the noise of the others.
    const Eigen::Vector3d e(noise->normal(), noise->normal(), noise->normal());
    if (keep[j]) points.push_back(p + o.noise_mm * e);
  }
  return points;
}

void add_truth(const ProfileDeformation& shape, const std::string& id, int i, double tx, double ty,
               std::vector<ProfileTruthRow>* truth) {
  truth->push_back({id, i, tx, ty, shape.map(tx, ty)});
}

}  // namespace

bool ProfileScanOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!deformation.IsValid(&problem)) {
  } else if (!(spacing_mm > 0.0) || spacing_mm > deformation.length_mm / 3.0) {
    problem = "spacing_mm must be positive and give at least 4 samples along the length";
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    problem = "noise_mm must be >= 0";
  } else if (!(dropout_fraction >= 0.0 && dropout_fraction <= 0.5)) {
    problem = "dropout_fraction must be in [0, 0.5]";
  } else if (holes < 0 || holes > 100000) {
    problem = "holes must be in [0, 100000]";
  } else if (holes > 0 && (!(hole_radius_mm > 0.0) || 2.0 * hole_radius_mm >= deformation.length_mm / holes)) {
    problem = "hole_radius_mm must be positive and the holes must not overlap along the length";
  } else if (!std::isfinite(hole_tx_mm)) {
    problem = "hole_tx_mm must be finite";
  } else if (outliers < 0 || !(outlier_mm > 0.0) || !std::isfinite(outlier_mm)) {
    problem = "outliers must be >= 0 and outlier_mm positive";
  } else if (!offset_mm.allFinite()) {
    problem = "offset_mm must be finite";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

ProfileScan generate_profile_scan(const ProfileScanOptions& o) {
  std::string problem;
  if (!o.IsValid(&problem)) throw Error("generate profile: " + problem);
  const ProfileDeformation shape(o.deformation);
  const double L = o.deformation.length_mm;
  const std::size_t samples = static_cast<std::size_t>(std::floor(L / o.spacing_mm + 1e-9)) + 1;

  ProfileScan scan;
  std::vector<bool> keep(samples, true);
  Random dropout(o.seed, kDropoutStream);
  for (std::size_t j = 1; j + 1 < samples; ++j) {
    keep[j] = !(dropout.uniform() < o.dropout_fraction);
    if (!keep[j]) ++scan.dropped;
  }
  Random noise(o.seed, kEdgeNoiseStream);
  scan.edge = sample_edge(shape, o, 0.0, keep, &noise);
  if (o.second_edge) {
    Random second(o.seed, kSecondEdgeNoiseStream);
    scan.second_edge = sample_edge(shape, o, o.deformation.width_mm, keep, &second);
  }
  add_outliers(o, &scan.edge, &scan.outlier_indices);
  for (Eigen::Vector3d& p : scan.edge) p += o.offset_mm;
  for (Eigen::Vector3d& p : scan.second_edge) p += o.offset_mm;
  if (o.reversed) {
    std::reverse(scan.edge.begin(), scan.edge.end());
    std::reverse(scan.second_edge.begin(), scan.second_edge.end());
    for (std::size_t& i : scan.outlier_indices) i = scan.edge.size() - 1 - i;
    std::sort(scan.outlier_indices.begin(), scan.outlier_indices.end());
  }
  for (int k = 0; k < o.holes; ++k) {
    const std::string id = "H" + std::to_string(k + 1);
    const double ty = L * (k + 0.5) / o.holes;
    scan.features.push_back({id, "circle", o.hole_tx_mm, ty, o.hole_radius_mm});
    add_truth(shape, id, -1, o.hole_tx_mm, ty, &scan.truth);
  }
  if (o.marking_line) {
    const double tx = 0.5 * o.deformation.width_mm;
    const double ty[3] = {0.05 * L, 0.5 * L, 0.95 * L};
    for (int i = 0; i < 3; ++i) {
      scan.features.push_back({"M1", "polyline", tx, ty[i], 0.0});
      add_truth(shape, "M1", i, tx, ty[i], &scan.truth);
    }
  }
  for (ProfileTruthRow& t : scan.truth) t.position += o.offset_mm;
  return scan;
}

}  // namespace conform
