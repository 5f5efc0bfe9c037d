#include "conform/toolpath/weld/weld_layers.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "weld_layer_paths.h"

namespace conform {
namespace {

std::string fixed(double x, int decimals = 3) { return format_fixed(x, decimals); }

std::string where(const DamageRegion& r) {
  return "crater " + std::to_string(r.id) + " at (" + fixed(r.deepest.x(), 1) + ", " + fixed(r.deepest.y(), 1) + ", " +
         fixed(r.deepest.z(), 1) + ") mm (grid row " + std::to_string(r.deepest_row) + ", col " +
         std::to_string(r.deepest_col) + ", " + fixed(r.max_depth_mm) + " mm deep)";
}

// Densified path points in a kd-tree, each with its bead's half width: the share of some nodes that a bead covers.
class PathCloud {
 public:
  explicit PathCloud(const std::vector<const WeldPath*>& paths) {
    for (const WeldPath* path : paths) {
      const auto& p = path->points;
      const double radius = 0.5 * path->bead_width_mm;
      max_radius_ = std::max(max_radius_, radius);
      for (std::size_t i = 0; i < p.size(); ++i) {
        dense_.push_back(p[i]), radius_.push_back(radius);
        if (i + 1 == p.size()) break;
        const int pieces = static_cast<int>(std::ceil((p[i + 1] - p[i]).norm() / (radius / 8.0)));
        for (int k = 1; k < pieces; ++k) {
          dense_.push_back(p[i] + (p[i + 1] - p[i]) * (double(k) / pieces)), radius_.push_back(radius);
        }
      }
    }
    tree_ = std::make_unique<KdTree>(dense_);
  }
  double covered_pct(const std::vector<Eigen::Vector3d>& nodes) const {
    if (nodes.empty()) return 100.0;
    std::size_t covered = 0;
    std::vector<int> index;
    std::vector<float> d2;
    for (const Eigen::Vector3d& n : nodes) {
      tree_->radius(n.cast<float>(), static_cast<float>(max_radius_), index, d2);
      bool in = false;
      for (std::size_t k = 0; k < index.size() && !in; ++k) {
        in = std::sqrt(static_cast<double>(d2[k])) <= radius_[static_cast<std::size_t>(index[k])];
      }
      covered += in;
    }
    return 100.0 * static_cast<double>(covered) / static_cast<double>(nodes.size());
  }

 private:
  double max_radius_ = 0.0;
  std::vector<Eigen::Vector3d> dense_;
  std::vector<double> radius_;
  std::unique_ptr<KdTree> tree_;
};

// The length of each path of one layer within `radius` of another line of the layer (pieces of one half-step line are
// one bead): beads laid over beads. Sampled every radius / 4 along the paths.
double overlap_length(const std::vector<const WeldPath*>& layer, double radius) {
  std::vector<Eigen::Vector3d> dense;
  std::vector<int> line;
  const double step = 0.25 * radius;
  auto densify = [&](const WeldPath& path, const std::function<void(const Eigen::Vector3d&, double)>& visit) {
    for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
      const Eigen::Vector3d a = path.points[i], b = path.points[i + 1];
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
      for (int k = 0; k < pieces; ++k) visit(a + (b - a) * ((k + 0.5) / pieces), (b - a).norm() / pieces);
    }
  };
  for (const WeldPath* path : layer) {
    densify(*path, [&](const Eigen::Vector3d& x, double) { dense.push_back(x), line.push_back(path->line); });
    dense.push_back(path->points.back()), line.push_back(path->line);
  }
  if (dense.empty()) return 0.0;
  const KdTree tree(dense);
  double length = 0.0;
  std::vector<int> index;
  std::vector<float> d2;
  for (const WeldPath* path : layer) {
    densify(*path, [&](const Eigen::Vector3d& x, double piece) {
      tree.radius(x.cast<float>(), static_cast<float>(radius), index, d2);
      bool other = false;
      for (std::size_t k = 0; k < index.size() && !other; ++k) {
        other =
            line[static_cast<std::size_t>(index[k])] != path->line && std::sqrt(static_cast<double>(d2[k])) < radius;
      }
      if (other) length += piece;
    });
  }
  return length;
}

// Step 2: the rims, eroded against the reference offset inward by the threshold (and by the bias when removed).
void find_rims(const BezierNetwork& eroded, const BezierNetwork& reference, const WeldLayerOptions& options,
               WeldLayerResult* result) {
  const DamageMap& map = result->damage;
  SurfaceGrid grid{reference.patch_rows() + 1, reference.patch_cols() + 1, {}};
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const Eigen::Vector3d q = reference.position(c, r), n = reference.normal(c, r);
      grid.points.push_back(q + ((map.bias_removed ? map.bias_at(q) : 0.0) - map.outward_sign * map.threshold_mm) * n);
    }
  }
  IntersectionOptions io;
  io.tolerance_mm = options.intersection_tolerance_mm > 0.0 ? options.intersection_tolerance_mm
                                                            : options.bead_spacing_mm / 10.0;
  const IntersectionResult cut = intersect_surfaces(eroded, BezierNetwork(grid), io);
  result->box_pairs = cut.box_pairs;
  if (cut.work_limit_hit) throw Error("weld layers: boundary of the damage: " + cut.termination);
  if (!cut.ok) result->warnings.push_back("boundary of the damage: " + cut.termination);
  const ParameterDomain d = eroded.domain();
  const double link = io.link_factor * io.tolerance_mm;
  auto at_border = [&](const IntersectionPoint& p) {
    const double u = p.uv_a.x(), v = p.uv_a.y();
    const double du = eroded.derivative(u, v, 1, 0).norm(), dv = eroded.derivative(u, v, 0, 1).norm();
    return std::min(u - d.u_min, d.u_max - u) * du <= link || std::min(v - d.v_min, d.v_max - v) * dv <= link;
  };
  std::vector<IntersectionCurve> border;
  for (const IntersectionCurve& c : cut.curves) {
    if (c.closed) {
      result->rims.push_back(c);
    } else if (at_border(c.points.front()) && at_border(c.points.back())) {
      border.push_back(c);  // closed along the grid's border
    } else {
      ++result->open_curves;
    }
  }
  result->border_rims = border.size();
  result->rims.insert(result->rims.end(), border.begin(), border.end());
  for (const DamageRegion& region : map.regions) {
    bool found = false;
    for (const IntersectionCurve& c : cut.curves) {
      for (const IntersectionPoint& p : c.points) {
        found = found || (p.uv_a.x() >= region.col_min - 2 && p.uv_a.x() <= region.col_max + 2 &&
                          p.uv_a.y() >= region.row_min - 2 && p.uv_a.y() <= region.row_max + 2);
      }
    }
    if (!found) result->regions_without_rim.push_back(region.id);
  }
}

std::string bias_text(const DamageMap& map) {
  return "the eroded grid is offset " + fixed(map.bias_offset_mm) + " mm (+: outward) and tilted " +
         fixed(map.bias_tilt_deg, 3) + " deg against the reference (moves nodes by up to " + fixed(map.bias_span_mm) +
         " mm; noise " + fixed(map.noise_mm, 4) + " mm)";
}

// Step 1 and its verdicts; false (termination set) when the job cannot go on.
bool check_damage(const WeldLayerOptions& options, WeldLayerResult* result) {
  const DamageMap& map = result->damage;
  if (map.bias_significant) {
    if (options.bias == BiasMode::kCheck) {
      result->termination = bias_text(map) + ": register the grids, or --bias remove (a registration error) or "
                                             "--bias keep (uniform wear to refill)";
      return false;
    }
    result->warnings.push_back(bias_text(map) + (map.bias_removed ? ": removed" : ": kept as damage"));
  }
  if (map.off_reference > 0) {
    result->warnings.push_back(std::to_string(map.off_reference) +
                               " eroded nodes lie beyond the reference's border: not judged");
  }
  if (map.side_ambiguous) {
    result->termination = "which side of the reference is damage is ambiguous (volume beyond the threshold " +
                          fixed(map.side_ratio, 2) + " x the other side's): give --outward +1 or -1";
    return false;
  }
  if (map.regions.empty()) {
    result->termination = "no damage found: no eroded node is more than " + fixed(map.threshold_mm, 4) +
                          " mm below the reference (deepest " + fixed(map.max_depth_mm, 4) + " mm)";
    return false;
  }
  return true;
}

// Crossings between different paths of one layer and region, in the plane across the region's outward normal.
std::size_t crossings(const std::vector<const WeldPath*>& paths, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d e1 = (std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(normal).normalized();
  const Eigen::Vector3d e2 = normal.cross(e1);
  std::vector<std::vector<Eigen::Vector2d>> flat;
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const WeldPath* p : paths) {
    flat.emplace_back();
    boxes.emplace_back();
    for (const Eigen::Vector3d& x : p->points) flat.back().emplace_back(x.dot(e1), x.dot(e2)), boxes.back().extend(flat.back().back());
  }
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
    auto orient = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
      return (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
    };
    return orient(a, b, c) * orient(a, b, d) < 0.0 && orient(c, d, a) * orient(c, d, b) < 0.0;
  };
  std::size_t count = 0;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    for (std::size_t j = i + 1; j < flat.size(); ++j) {
      if (!boxes[i].intersects(boxes[j])) continue;
      for (std::size_t a = 0; a + 1 < flat[i].size(); ++a) {
        for (std::size_t b = 0; b + 1 < flat[j].size(); ++b) count += cross(flat[i][a], flat[i][a + 1], flat[j][b], flat[j][b + 1]);
      }
    }
  }
  return count;
}

// Step 5 and the honest status: coverage of the damage per region and per layer, empty layers, max paths.
void judge(const BezierNetwork& eroded, const WeldLayerOptions& options,
           const std::vector<std::vector<Eigen::Vector3d>>& layer_nodes, WeldLayerResult* result) {
  const DamageMap& map = result->damage;
  std::vector<std::string> failures;
  result->coverage_pct_min = 100.0;
  for (int k = 1; k <= result->layers; ++k) {
    std::vector<const WeldPath*> layer;
    for (const WeldPath& p : result->paths) {
      if (p.layer == k) layer.push_back(&p);
    }
    const PathCloud cloud(layer);
    const std::vector<Eigen::Vector3d>& nodes = layer_nodes[static_cast<std::size_t>(k - 1)];
    const double pct = cloud.covered_pct(nodes);
    result->coverage_pct.push_back(pct);
    result->coverage_pct_min = std::min(result->coverage_pct_min, pct);
    const double area = static_cast<double>(nodes.size()) * map.regions.front().area_mm2 /
                        static_cast<double>(std::max<std::size_t>(map.regions.front().nodes, 1));
    if (layer.empty() && !nodes.empty()) {
      const std::string text = "layer " + std::to_string(k) + " has no path over its " + std::to_string(nodes.size()) +
                               " nodes (~" + fixed(area, 1) + " mm^2)";
      if (area >= options.bead_spacing_mm * options.bead_spacing_mm) {
        failures.push_back(text);
      } else {
        result->warnings.push_back(text + ": narrower than a bead");
      }
    } else if (nodes.empty()) {
      result->warnings.push_back("layer " + std::to_string(k) + " is empty: no damage left at its level");
    }
    for (const DamageRegion& region : map.regions) {
      std::vector<const WeldPath*> own;
      for (const WeldPath* p : layer) {
        if (p->region == region.id) own.push_back(p);
      }
      const std::size_t n = crossings(own, map.outward[static_cast<std::size_t>(region.deepest_row * map.cols + region.deepest_col)]);
      result->path_crossings += n;
      if (n > 0) {
        failures.push_back("layer " + std::to_string(k) + ", crater " + std::to_string(region.id) + ": its paths cross " +
                           std::to_string(n) + " times");
      }
    }
    const double overlap = overlap_length(layer, 0.5 * result->bead_width_mm);
    result->overlap_mm.push_back(overlap);
    result->overlap_mm_max = std::max(result->overlap_mm_max, overlap);
    if (overlap > options.max_overlap_mm) {
      failures.push_back("layer " + std::to_string(k) + ": " + fixed(overlap, 1) +
                         " mm of its paths lie within half a bead (" + fixed(0.5 * result->bead_width_mm, 2) +
                         " mm) of another of its paths (beads over beads; " + "limit " +
                         fixed(options.max_overlap_mm, 1) + " mm)");
    }
    if (k != 1) continue;
    for (const DamageRegion& region : map.regions) {
      std::vector<Eigen::Vector3d> own;
      for (int r = region.row_min; r <= region.row_max; ++r) {
        for (int c = region.col_min; c <= region.col_max; ++c) {
          if (map.label[static_cast<std::size_t>(r * map.cols + c)] == region.id) own.push_back(eroded.position(c, r));
        }
      }
      const double own_pct = cloud.covered_pct(own);
      result->crater_coverage_pct.push_back(own_pct);
      if (own_pct >= options.min_coverage_pct) continue;
      const std::string text = where(region) + ": layer 1 covers " + fixed(own_pct, 1) + " % of it";
      if (region.area_mm2 >= options.bead_spacing_mm * options.bead_spacing_mm &&
          own_pct < options.min_crater_coverage_pct) {
        failures.push_back(text);
      } else {
        result->warnings.push_back(text);
      }
    }
    result->damage_coverage_pct = pct;
  }
  for (int id : result->regions_without_rim) {
    result->warnings.push_back(where(map.regions[static_cast<std::size_t>(id - 1)]) + ": no rim found by the intersection");
  }
  if (result->open_curves > 0) {
    result->warnings.push_back(std::to_string(result->open_curves) + " rim pieces end inside the grid (broken rims)");
  }
  if (result->max_paths_reached) {
    failures.push_back(
        "max paths reached: the plan is partial (the half-step paths did not cross the crater: a bead "
        "spacing too small for its size, or paths that turn back in a tight bowl)");
  }
  if (result->damage_coverage_pct < options.min_coverage_pct) {
    failures.push_back("layer 1 covers " + fixed(result->damage_coverage_pct, 1) + " % of the damage (minimum " +
                       fixed(options.min_coverage_pct, 1) + " %)");
  }
  if (!failures.empty()) {
    result->termination = failures.front();
    for (std::size_t i = 1; i < failures.size(); ++i) result->termination += "; " + failures[i];
    return;
  }
  result->ok = true;
  result->termination = "planned";
}

}  // namespace

bool WeldLayerOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(bead_spacing_mm) || bead_spacing_mm > 100.0) return fail("bead spacing must be in (0, 100] mm");
  if (!positive(layer_height_mm) || layer_height_mm > 100.0) return fail("layer height must be in (0, 100] mm");
  if (!positive(chord_error_mm) || chord_error_mm > 0.5 * bead_spacing_mm) {
    return fail("chord error must be > 0 mm and at most half the bead spacing");
  }
  if (!(torch_distance_mm >= 0.0) || !(torch_distance_mm <= kMaxTorchDistanceMm)) {
    return fail("torch distance must be in [0, " + format_fixed(kMaxTorchDistanceMm, 0) + "] mm");
  }
  if (layers < 0 || layers > kMaxWeldLayers) {
    return fail("layers must be in [0, " + std::to_string(kMaxWeldLayers) + "] (0: as many as the depth needs)");
  }
  if (!std::isfinite(depth_threshold_mm) || depth_threshold_mm > 1000.0) return fail("depth threshold must be finite");
  if (outward_side < -1 || outward_side > 1) return fail("outward side must be -1, 0 (from the data) or +1");
  if (!(min_coverage_pct >= 0.0 && min_coverage_pct <= 100.0)) return fail("minimum coverage must be in [0, 100] %");
  if (!(bead_width_mm >= 0.0) || bead_width_mm > 100.0)
    return fail("bead width must be in [0, 100] mm (0: the spacing)");
  if (!(max_overlap_mm >= 0.0) || !std::isfinite(max_overlap_mm)) return fail("max overlap must be >= 0 mm");
  if (!(min_crater_coverage_pct >= 0.0 && min_crater_coverage_pct <= 100.0)) {
    return fail("minimum crater coverage must be in [0, 100] %");
  }
  if (!(intersection_tolerance_mm >= 0.0) || !std::isfinite(intersection_tolerance_mm)) {
    return fail("intersection tolerance must be >= 0 mm");
  }
  if (!(max_step_mm >= 0.0) || !std::isfinite(max_step_mm) || (max_step_mm > 0.0 && max_step_mm <= chord_error_mm)) {
    return fail("max step must be 0 (2 dc) or exceed the chord error");
  }
  if (smoothing_passes > 50) return fail("smoothing passes must be at most 50 (< 0: from the grid spacing)");
  return true;
}

double WeldPath::length_mm() const {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

WeldLayerResult plan_weld_layers(const BezierNetwork& eroded, const BezierNetwork& reference,
                                 const WeldLayerOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error("weld layers: " + error);
  WeldLayerResult result;
  DamageOptions damage;
  damage.depth_threshold_mm = options.depth_threshold_mm;
  damage.outward_side = options.outward_side;
  damage.bias = options.bias;
  result.damage = map_damage(eroded, reference, damage);
  const DamageMap& map = result.damage;
  result.noise_mm = map.noise_mm;
  result.depth_threshold_mm = map.threshold_mm;
  result.threshold_estimated = map.threshold_estimated;
  result.max_depth_mm = map.max_depth_mm;
  if (!check_damage(options, &result)) return result;
  const double needed = std::ceil((map.max_depth_mm - map.threshold_mm) / options.layer_height_mm);
  if (options.layers == 0 && needed > kMaxWeldLayers) {
    throw Error("weld layers: the damage (" + fixed(map.max_depth_mm) + " mm deep) needs " + fixed(needed, 0) +
                " layers of " + fixed(options.layer_height_mm, 4) + " mm (limit kMaxWeldLayers " +
                std::to_string(kMaxWeldLayers) + "): raise --layer-height");
  }
  result.layers = options.layers > 0 ? options.layers : std::max(1, static_cast<int>(needed));
  result.bead_width_mm = options.bead_width_mm > 0.0 ? options.bead_width_mm : options.bead_spacing_mm;
  find_rims(eroded, reference, options, &result);
  std::vector<std::vector<Eigen::Vector3d>> layer_nodes(static_cast<std::size_t>(result.layers));
  result.paths_per_layer.assign(static_cast<std::size_t>(result.layers), 0);
  for (int k = 1; k <= result.layers; ++k) {
    for (const DamageRegion& region : map.regions) {
      detail::LayerPlan plan = detail::plan_layer(eroded, map, region.id, k, options);
      auto& nodes = layer_nodes[static_cast<std::size_t>(k - 1)];
      nodes.insert(nodes.end(), plan.region_nodes.begin(), plan.region_nodes.end());
      result.half_step_paths += plan.half_step_paths;
      result.loops_removed += plan.loops_removed;
      result.cusps_removed += plan.cusps_removed;
      result.newton_offsets += plan.newton_offsets;
      result.chord_error_mm_max = std::max(result.chord_error_mm_max, plan.chord_error_mm_max);
      result.spacing_error_pct_max = std::max(result.spacing_error_pct_max, plan.spacing_error_pct_max);
      result.max_paths_reached = result.max_paths_reached || plan.max_paths_reached;
      result.crossings_cut += plan.crossings_cut;
      result.lines_turned_back += plan.lines_turned_back;
      for (WeldPath& path : plan.paths) {
        path.path = ++result.paths_per_layer[static_cast<std::size_t>(k - 1)];
        result.total_length_mm += path.length_mm();
        result.paths.push_back(std::move(path));
      }
    }
  }
  judge(eroded, options, layer_nodes, &result);
  return result;
}

}  // namespace conform
