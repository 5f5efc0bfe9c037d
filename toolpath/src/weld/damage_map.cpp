#include "conform/toolpath/weld/damage_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {
namespace {

constexpr double kNormalSigma = 1.4826;  // sigma / MAD for normal data

struct SignedDistances {
  std::vector<double> d;                 // along the reference's r_u x r_v
  std::vector<Eigen::Vector3d> normal;   // the reference's r_u x r_v at the closest point
  std::vector<bool> valid;               // false: the closest point is on the reference's border, the node beyond it
};

// Step 1: closest points by Newton from the nearest reference node (kd-tree over the nodes).
SignedDistances signed_distances(const BezierNetwork& eroded, const BezierNetwork& reference, double max_deviation) {
  std::vector<Eigen::Vector3d> nodes;
  const int rr = reference.patch_rows() + 1, rc = reference.patch_cols() + 1;
  nodes.reserve(static_cast<std::size_t>(rr) * static_cast<std::size_t>(rc));
  for (int r = 0; r < rr; ++r) {
    for (int c = 0; c < rc; ++c) nodes.push_back(reference.position(c, r));
  }
  const KdTree tree(nodes);
  const ParameterDomain dom = reference.domain();
  const int rows = eroded.patch_rows() + 1, cols = eroded.patch_cols() + 1;
  SignedDistances out;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector3d p = eroded.position(c, r);
      const int k = tree.nearest(p.cast<float>());
      double u = k % rc, v = k / rc;
      project_to_surface(reference, p, &u, &v);
      const Eigen::Vector3d q = reference.position(u, v), n = reference.normal(u, v);
      const double d = (p - q).dot(n);
      if (!(std::abs(d) <= max_deviation)) {
        throw Error("eroded grid row " + std::to_string(r) + ", col " + std::to_string(c) + " lies " +
                    format_fixed(std::abs(d), 3) + " mm from the reference (limit max_deviation_mm " +
                    format_fixed(max_deviation, 1) + "): an outlier, or grids of different surfaces");
      }
      const double tangential = ((p - q) - d * n).norm();
      const double spacing = std::min(reference.derivative(u, v, 1, 0).norm(), reference.derivative(u, v, 0, 1).norm());
      const bool on_border = !dom.contains(u, v, -1e-9);
      out.d.push_back(d);
      out.normal.push_back(n);
      out.valid.push_back(!(on_border && tangential > 0.25 * spacing));
    }
  }
  return out;
}

struct Plane {
  double a = 0.0;
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  double at(const Eigen::Vector3d& p) const { return a + b.x() * (p - centre).dot(e1) + b.y() * (p - centre).dot(e2); }
};

// Least squares d = a + b . (p - centre) over the nodes marked `in`; false when they do not determine a plane.
bool fit_plane(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& d, const std::vector<bool>& in,
               Plane* plane) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!in[i]) continue;
    const Eigen::Vector3d x(1.0, (points[i] - plane->centre).dot(plane->e1),
                            (points[i] - plane->centre).dot(plane->e2));
    A += x * x.transpose();
    rhs += x * d[i];
    ++n;
  }
  if (n < 3) return false;
  const Eigen::Vector3d sol = A.ldlt().solve(rhs);
  if (!sol.allFinite()) return false;
  plane->a = sol[0], plane->b = sol.tail<2>();
  return true;
}

// The level most residuals agree on: the fullest bin of width `bin` (smoothed over 3 bins), refined to the mean of
// the residuals within one bin of it. A lip or a crater floor is a smaller level than the undamaged surface.
double residual_mode(const std::vector<double>& residual, double bin) {
  if (residual.empty()) return 0.0;
  const auto [lo, hi] = std::minmax_element(residual.begin(), residual.end());
  const int bins = std::min(static_cast<int>((*hi - *lo) / bin) + 1, 100000);
  const double width = std::max(bin, (*hi - *lo) / bins);
  std::vector<std::size_t> count(static_cast<std::size_t>(bins) + 2, 0);
  for (double x : residual)
    ++count[static_cast<std::size_t>(std::min(static_cast<int>((x - *lo) / width), bins - 1)) + 1];
  std::size_t best = 1, best_count = 0;
  for (std::size_t k = 1; k + 1 < count.size(); ++k) {
    const std::size_t c = count[k - 1] + 2 * count[k] + count[k + 1];
    if (c > best_count) best = k, best_count = c;
  }
  const double centre = *lo + (static_cast<double>(best) - 0.5) * width;
  double sum = 0.0;
  std::size_t n = 0;
  for (double x : residual) {
    if (std::abs(x - centre) <= width) sum += x, ++n;
  }
  return n > 0 ? sum / static_cast<double>(n) : centre;
}

// Step 2: the bias plane from the undamaged surface only. d = a + b . (p - centre) in the plane across the mean
// normal: a trimmed least-squares start (3 robust sigmas around the median), then a band around the mode of the
// residuals shrunk by halves down to `band` (3 noise sigmas) and refitted, and last a fit on the band's nodes that are
// at least `margin` nodes away from every feature (a node beyond `feature` from the plane: a crater, lip or bump). So
// raised material and the foot of a crater's slope stay out of it however much of the grid they cover, as long as
// the undamaged surface is the most common level.
Plane bias_plane(const std::vector<Eigen::Vector3d>& points, const SignedDistances& s, int rows, int cols, double band,
                 double feature, int margin) {
  Plane plane;
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (s.valid[i]) plane.centre += points[i], mean_normal += s.normal[i], ++n;
  }
  if (n < 3) return plane;
  plane.centre /= static_cast<double>(n);
  const Eigen::Vector3d z = mean_normal.normalized();
  plane.e1 = (std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(z).normalized();
  plane.e2 = z.cross(plane.e1);
  std::vector<double> valid_d;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (s.valid[i]) valid_d.push_back(s.d[i]);
  }
  plane.a = median_of(valid_d);  // a robust start: the level most nodes agree on
  std::vector<bool> in(points.size(), false);
  auto residuals = [&] {
    std::vector<double> residual;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (s.valid[i]) residual.push_back(s.d[i] - plane.at(points[i]));
    }
    return residual;
  };
  double limit = 0.0;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const std::vector<double> residual = residuals();
    const double centre = median_of(residual);
    limit = std::max(3.0 * robust_sigma(residual), 1e-9);
    for (std::size_t i = 0; i < points.size(); ++i) {
      in[i] = s.valid[i] && std::abs(s.d[i] - plane.at(points[i]) - centre) <= limit;
    }
    if (!fit_plane(points, s.d, in, &plane)) break;
  }
  for (int iteration = 0; iteration < 40; ++iteration) {
    limit = std::max(0.5 * limit, band);
    const double mode = residual_mode(residuals(), band / 3.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      in[i] = s.valid[i] && std::abs(s.d[i] - plane.at(points[i]) - mode) <= limit;
    }
    const Plane before = plane;
    if (!fit_plane(points, s.d, in, &plane)) return before;
    if (limit == band && std::abs(plane.a - before.a) < 1e-3 * band && (plane.b - before.b).norm() < 1e-6) break;
  }
  // Away from the features: dilate them by `margin` nodes (a square, rows then columns) and fit on the rest of the
  // band.
  auto at = [&](int r, int c) { return static_cast<std::size_t>(r * cols + c); };
  std::vector<char> near(points.size(), 0), along_rows(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    near[i] = s.valid[i] && std::abs(s.d[i] - plane.at(points[i])) > feature;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      for (int k = std::max(0, c - margin); k <= std::min(cols - 1, c + margin) && !along_rows[at(r, c)]; ++k) {
        along_rows[at(r, c)] = near[at(r, k)];
      }
    }
  }
  std::vector<bool> quiet = in;
  std::size_t quiet_nodes = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      bool touched = false;
      for (int k = std::max(0, r - margin); k <= std::min(rows - 1, r + margin) && !touched; ++k)
        touched = along_rows[at(k, c)];
      quiet[at(r, c)] = quiet[at(r, c)] && !touched;
      quiet_nodes += quiet[at(r, c)];
    }
  }
  Plane refined = plane;
  if (quiet_nodes >= std::max<std::size_t>(16, n / 20) && fit_plane(points, s.d, quiet, &refined)) return refined;
  return plane;
}

// Step 3: sigma of the local residuals e = d - mean of the 4 neighbours (white noise: variance 5/4 sigma^2), by the
// median of |e|. A crater's curvature gives its nodes residuals of ~h^2/4 |Laplacian|, which would still pull the
// median up when craters cover a good share of the grid: a second pass leaves out the nodes beyond 6 first-pass sigmas
// from the bias plane (and their neighbours), the features, and takes the median over the rest.
double local_noise(const std::vector<double>& d, const std::vector<double>& plane, const std::vector<bool>& valid,
                   int rows, int cols, bool second_pass = true) {
  auto at = [&](int r, int c) { return static_cast<std::size_t>(r * cols + c); };
  auto sigma = [&](const std::vector<bool>& use) {
    std::vector<double> magnitude;
    for (int r = 1; r + 1 < rows; ++r) {
      for (int c = 1; c + 1 < cols; ++c) {
        const std::size_t k[5] = {at(r, c), at(r - 1, c), at(r + 1, c), at(r, c - 1), at(r, c + 1)};
        if (!(use[k[0]] && use[k[1]] && use[k[2]] && use[k[3]] && use[k[4]])) continue;
        magnitude.push_back(std::abs(d[k[0]] - 0.25 * (d[k[1]] + d[k[2]] + d[k[3]] + d[k[4]])));
      }
    }
    return magnitude.size() < 8 ? -1.0 : kNormalSigma * median_of(std::move(magnitude)) / std::sqrt(1.25);
  };
  const double first = std::max(sigma(valid), 0.0);
  if (!second_pass) return first;
  std::vector<bool> quiet = valid;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (!valid[at(r, c)] || std::abs(d[at(r, c)] - plane[at(r, c)]) <= 6.0 * first) continue;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (r + dr >= 0 && c + dc >= 0 && r + dr < rows && c + dc < cols) quiet[at(r + dr, c + dc)] = false;
        }
      }
    }
  }
  const double second = sigma(quiet);
  return second >= 0.0 ? second : first;
}

// A crater's fringe sinks below the threshold gradually: there noise splits the nodes beyond it into the main
// region and islands a node or two away (a blade's 15 mm crater at 0.02 mm noise: two islands inside its rim, each
// planned as a crater of its own, their beads laid over the crater's). So the regions are grouped by hysteresis, as
// edges are in Canny 1986: nodes beyond the threshold belong to one region when a chain of 8-connected nodes deeper
// than kHysteresis times the threshold joins them. Only the nodes beyond the threshold are the region's.
constexpr double kHysteresis = 0.5;

// Step 5: the damaged regions by decreasing volume: the nodes deeper than the threshold, grouped by the
// 8-connected components of the nodes deeper than kHysteresis times it.
void label_regions(const BezierNetwork& eroded, DamageMap* map) {
  const int rows = map->rows, cols = map->cols;
  const double low = kHysteresis * map->threshold_mm;
  const auto deep = [&](std::size_t k, double level) { return map->depth[k] > level; };
  std::vector<int> group(map->depth.size(), 0);
  std::vector<int> stack;
  int groups = 0;
  for (int start = 0; start < rows * cols; ++start) {
    if (group[static_cast<std::size_t>(start)] != 0 || !deep(static_cast<std::size_t>(start), low)) continue;
    group[static_cast<std::size_t>(start)] = ++groups;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const int r = k / cols, c = k % cols;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int rn = r + dr, cn = c + dc;
          if (rn < 0 || cn < 0 || rn >= rows || cn >= cols) continue;
          const auto kn = static_cast<std::size_t>(rn * cols + cn);
          if (group[kn] == 0 && deep(kn, low)) group[kn] = groups, stack.push_back(rn * cols + cn);
        }
      }
    }
  }
  map->label.assign(map->depth.size(), 0);
  std::vector<int> region_of(static_cast<std::size_t>(groups) + 1, 0);  // group -> region id, 0: none yet
  std::vector<DamageRegion> regions;
  for (int k = 0; k < rows * cols; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (!deep(kk, map->threshold_mm)) continue;
    int& id = region_of[static_cast<std::size_t>(group[kk])];
    if (id == 0) {
      DamageRegion region;
      region.id = id = static_cast<int>(regions.size()) + 1;
      region.row_min = rows, region.col_min = cols, region.row_max = -1, region.col_max = -1;
      regions.push_back(region);
    }
    map->label[kk] = id;
    DamageRegion& region = regions[static_cast<std::size_t>(id - 1)];
    const int r = k / cols, c = k % cols;
    const double depth = map->depth[kk];
    const double area = eroded.derivative(c, r, 1, 0).cross(eroded.derivative(c, r, 0, 1)).norm();
    ++region.nodes;
    region.area_mm2 += area;
    region.volume_mm3 += (depth - map->threshold_mm) * area;
    if (depth > region.max_depth_mm) {
      region.max_depth_mm = depth, region.deepest = eroded.position(c, r), region.deepest_row = r, region.deepest_col = c;
    }
    region.at_border = region.at_border || r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
    region.row_min = std::min(region.row_min, r), region.row_max = std::max(region.row_max, r);
    region.col_min = std::min(region.col_min, c), region.col_max = std::max(region.col_max, c);
  }
  std::vector<int> order(regions.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return regions[static_cast<std::size_t>(x)].volume_mm3 > regions[static_cast<std::size_t>(y)].volume_mm3;
  });
  std::vector<int> new_id(regions.size() + 1, 0);
  for (std::size_t i = 0; i < order.size(); ++i) {
    new_id[static_cast<std::size_t>(order[i]) + 1] = static_cast<int>(i) + 1;
    map->regions.push_back(regions[static_cast<std::size_t>(order[i])]);
    map->regions.back().id = static_cast<int>(i) + 1;
  }
  for (int& l : map->label) l = new_id[static_cast<std::size_t>(l)];
}

}  // namespace

double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

double robust_sigma(const std::vector<double>& values) {
  const double m = median_of(values);
  std::vector<double> deviation;
  deviation.reserve(values.size());
  for (double x : values) deviation.push_back(std::abs(x - m));
  return kNormalSigma * median_of(std::move(deviation));
}

bool DamageOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!std::isfinite(depth_threshold_mm) || depth_threshold_mm > 1000.0) return fail("depth threshold must be finite, <= 1000 mm");
  if (!(noise_factor > 0.0) || noise_factor > 100.0) return fail("noise factor must be in (0, 100]");
  if (!(min_threshold_mm >= 0.0) || !std::isfinite(min_threshold_mm)) return fail("minimum threshold must be >= 0 mm");
  if (outward_side < -1 || outward_side > 1) return fail("outward side must be -1, 0 (from the data) or +1");
  if (!(bias_tolerance_mm >= 0.0) || !std::isfinite(bias_tolerance_mm)) return fail("bias tolerance must be >= 0 mm");
  if (!(bias_margin_mm >= 0.0) || bias_margin_mm > 1000.0) return fail("bias margin must be in [0, 1000] mm");
  if (!(side_ratio_min >= 1.0) || !std::isfinite(side_ratio_min)) return fail("side ratio must be >= 1");
  if (!(max_deviation_mm > 0.0) || !std::isfinite(max_deviation_mm)) return fail("max deviation must be > 0 mm");
  return true;
}

DamageMap map_damage(const BezierNetwork& eroded, const BezierNetwork& reference, const DamageOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error("damage map: " + error);
  DamageMap map;
  map.rows = eroded.patch_rows() + 1, map.cols = eroded.patch_cols() + 1;
  const SignedDistances s = signed_distances(eroded, reference, options.max_deviation_mm);
  std::vector<Eigen::Vector3d> points;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) points.push_back(eroded.position(c, r));
  }
  map.off_reference = static_cast<std::size_t>(std::count(s.valid.begin(), s.valid.end(), false));
  // The noise before the plane (its first pass needs none) sets the band the plane is fitted in.
  const std::vector<double> zero(points.size(), 0.0);
  const double first_noise = local_noise(s.d, zero, s.valid, map.rows, map.cols, false);
  const double spacing = std::max(eroded.derivative(0.5 * map.cols, 0.5 * map.rows, 1, 0).norm(), 1e-9);
  const double floor = 0.25 * std::max(options.min_threshold_mm, 1e-6);
  const Plane plane = bias_plane(points, s, map.rows, map.cols, std::max(3.0 * first_noise, floor),
                                 std::max(options.noise_factor * first_noise, options.min_threshold_mm),
                                 std::max(1, static_cast<int>(std::ceil(options.bias_margin_mm / spacing))));
  std::vector<double> plane_at;
  for (const Eigen::Vector3d& p : points) plane_at.push_back(plane.at(p));
  map.noise_mm = local_noise(s.d, plane_at, s.valid, map.rows, map.cols);
  for (const Eigen::Vector3d& p : points) map.bias_span_mm = std::max(map.bias_span_mm, std::abs(plane.at(p)));
  map.bias_tilt_deg = std::atan(plane.b.norm()) * 180.0 / kPi;
  map.bias_significant = map.bias_span_mm > std::max(options.bias_tolerance_mm, 3.0 * map.noise_mm);
  map.bias_removed = options.bias == BiasMode::kRemove;
  std::vector<double> d = s.d;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (map.bias_removed) d[i] -= plane.at(points[i]);
    if (!s.valid[i]) d[i] = 0.0;
  }
  map.threshold_estimated = options.depth_threshold_mm < 0.0;
  map.threshold_mm = map.threshold_estimated ? std::max(options.noise_factor * map.noise_mm, options.min_threshold_mm)
                                             : options.depth_threshold_mm;
  // Step 4: the side with more volume beyond the threshold is the damage (node areas ~ equal: counts suffice).
  double below = 0.0, above = 0.0;  // beyond -t and +t along r_u x r_v
  for (double x : d) below += std::max(-x - map.threshold_mm, 0.0), above += std::max(x - map.threshold_mm, 0.0);
  map.side_from_data = options.outward_side == 0;
  map.outward_sign = map.side_from_data ? (below >= above ? 1 : -1) : options.outward_side;
  const double damage_side = map.outward_sign > 0 ? below : above, other = map.outward_sign > 0 ? above : below;
  map.side_ratio = other > 0.0 ? damage_side / other : std::numeric_limits<double>::infinity();
  map.side_ambiguous = map.side_from_data && other > 0.0 && map.side_ratio < options.side_ratio_min;
  map.bias_offset_mm = map.outward_sign * plane.a;
  map.bias_a = plane.a, map.bias_b = plane.b, map.bias_centre = plane.centre, map.bias_e1 = plane.e1, map.bias_e2 = plane.e2;
  for (std::size_t i = 0; i < d.size(); ++i) {
    map.depth.push_back(-map.outward_sign * d[i]);
    map.outward.push_back(map.outward_sign * s.normal[i]);
    map.max_depth_mm = std::max(map.max_depth_mm, map.depth.back());
  }
  label_regions(eroded, &map);
  return map;
}

double damage_coverage_pct(const BezierNetwork& eroded, const DamageMap& map,
                           const std::vector<std::vector<Eigen::Vector3d>>& polylines, double radius_mm) {
  std::vector<Eigen::Vector3d> dense;
  const double step = radius_mm / 8.0;
  for (const auto& line : polylines) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      dense.push_back(line[i]);
      if (i + 1 == line.size()) break;
      const int pieces = static_cast<int>(std::ceil((line[i + 1] - line[i]).norm() / step));
      for (int k = 1; k < pieces; ++k) dense.push_back(line[i] + (line[i + 1] - line[i]) * (double(k) / pieces));
    }
  }
  std::size_t damaged = 0, covered = 0;
  const KdTree tree(dense);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      if (!(map.at(r, c) > map.threshold_mm)) continue;
      ++damaged;
      float d2 = std::numeric_limits<float>::infinity();
      if (!dense.empty()) tree.nearest(eroded.position(c, r).cast<float>(), &d2);
      if (std::sqrt(static_cast<double>(d2)) <= radius_mm) ++covered;
    }
  }
  return damaged == 0 ? 100.0 : 100.0 * static_cast<double>(covered) / static_cast<double>(damaged);
}

}  // namespace conform
