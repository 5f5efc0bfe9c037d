#pragma once
// `generate profile`: a deformed ship profile (profile_deformation.h) as a laser profile sensor measures it, with its
// designed features and the ground truth of where each designed point lies on the deformed profile.
//
// The sensor walks the edge from the origin: a sample every spacing_mm of arc length (s = 0, spacing, ... <= L),
// each moved by gaussian noise of sigma noise_mm in every coordinate; a fraction of the samples drop out (never the
// first or the last, so the edge's ends stay measured). The second edge (Tx = width) is sampled the same way with its
// own noise. Features: `holes` circles of hole_radius_mm at Tx = hole_tx_mm, centred at Ty = L (k + 1/2) / holes
// (the paper's experiment: five R50 holes at Tx = 100 along a 12,000 x 370 mm profile); optionally a marking line.
// Realistic faults on request: bad readings (outliers), the shop frame far from the origin (offset), and the edge
// listed from the far end (reversed; the ground truth stays in design coordinates).

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/datasets/profile_deformation.h"

namespace conform {

struct ProfileScanOptions {
  ProfileDeformationOptions deformation;
  double spacing_mm = 5.0;        // sample step along the edge (> 0)
  double noise_mm = 0.1;          // gaussian sigma per coordinate (>= 0)
  double dropout_fraction = 0.0;  // of the samples, dropped at random, in [0, 0.5]
  bool second_edge = false;       // also measure the edge at Tx = width
  int holes = 5;                  // circles evenly along the profile (>= 0)
  double hole_radius_mm = 50.0;   // (> 0)
  double hole_tx_mm = 100.0;      // their centres' Tx
  bool marking_line = false;      // a polyline along Tx = width / 2 from 5 % to 95 % of L, through its middle
  int outliers = 0;               // edge samples (never the first or last) moved off the edge by outlier_mm (>= 0)
  double outlier_mm = 30.0;       // across the web or along its normal, sign at random (> 0)
  Eigen::Vector3d offset_mm = Eigen::Vector3d::Zero();  // the shop frame: every point, edge and truth, moved by it
  bool reversed = false;          // the sensor walked from the far end: the edge points listed from Ty = L to 0
  std::uint64_t seed = 1;

  bool IsValid(std::string* error) const;
};

// One row of the designed features CSV: `id,type,tx_mm,ty_mm,radius_mm` (profile features in compensation/).
struct ProfileDesignRow {
  std::string id;
  std::string type;  // "circle", "polyline", ...
  double tx_mm = 0.0;
  double ty_mm = 0.0;
  double radius_mm = 0.0;
};

// Where a designed point lies on the deformed profile: circle centres as i = -1, vertices as i = 0, 1, ...
struct ProfileTruthRow {
  std::string id;
  int i = 0;
  double tx_mm = 0.0;
  double ty_mm = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct ProfileScan {
  std::vector<Eigen::Vector3d> edge;         // measured edge points, in measuring order
  std::vector<Eigen::Vector3d> second_edge;  // empty unless asked for
  std::vector<ProfileDesignRow> features;
  std::vector<ProfileTruthRow> truth;
  std::size_t dropped = 0;  // samples dropped from the edge
  std::vector<std::size_t> outlier_indices;  // indices into edge of the moved samples (in the listed order)
};

// Throws conform::Error when the options are invalid or a feature falls off the profile's length.
ProfileScan generate_profile_scan(const ProfileScanOptions& options);

}  // namespace conform
