#include "weld_layer_paths.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"
#include "conform/fitting/surface_grid.h"
#include "conform/toolpath/weld/parallel_paths.h"

namespace conform::detail {
namespace {

// `passes` binomial [1 2 1] / 4 passes along rows and columns (ends kept): the paths' Eq. (5) uses curvature, a
// second derivative that the measurement noise would dominate.
SurfaceGrid smoothed(SurfaceGrid grid, int passes) {
  for (int pass = 0; pass < passes; ++pass) {
    SurfaceGrid next = grid;
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 1; c + 1 < grid.cols; ++c) next.at(r, c) = 0.25 * (grid.at(r, c - 1) + 2.0 * grid.at(r, c) + grid.at(r, c + 1));
    }
    grid = next;
    for (int r = 1; r + 1 < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) next.at(r, c) = 0.25 * (grid.at(r - 1, c) + 2.0 * grid.at(r, c) + grid.at(r + 1, c));
    }
    grid = next;
  }
  return grid;
}

// One layer over a sub-grid [r0, r1] x [c0, c1] of the eroded grid: its surface (raw and smoothed) and its remaining
// depth below the threshold as a scalar spline (z of a network over (c, r)), all in sub-grid parameters.
struct LayerSurface {
  int r0 = 0, c0 = 0;
  BezierNetwork raw, smooth, remaining;
  const DamageMap* map = nullptr;
  int region = 0;

  // Inside the layer's part of the region: remaining depth > 0, and the cell is not another region's.
  bool inside(const Eigen::Vector2d& uv) const {
    if (!(remaining.position(uv.x(), uv.y()).z() > 0.0)) return false;
    const int c = std::clamp(static_cast<int>(std::floor(uv.x())), 0, raw.patch_cols() - 1) + c0;
    const int r = std::clamp(static_cast<int>(std::floor(uv.y())), 0, raw.patch_rows() - 1) + r0;
    bool other = false;
    for (int dr = 0; dr <= 1; ++dr) {
      for (int dc = 0; dc <= 1; ++dc) {
        const int l = map->label[static_cast<std::size_t>((r + dr) * map->cols + c + dc)];
        if (l == region) return true;
        other = other || l != 0;
      }
    }
    return !other;
  }
};

LayerSurface layer_surface(const BezierNetwork& eroded, const DamageMap& map, int region, double level, double cut,
                           int r0, int r1, int c0, int c1, int passes) {
  LayerSurface s;
  s.r0 = r0, s.c0 = c0, s.map = &map, s.region = region;
  SurfaceGrid lifted{r1 - r0 + 1, c1 - c0 + 1, {}}, remaining{r1 - r0 + 1, c1 - c0 + 1, {}};
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const std::size_t k = static_cast<std::size_t>(r * map.cols + c);
      lifted.points.push_back(eroded.position(c, r) + level * map.outward[k]);
      remaining.points.emplace_back(c - c0, r - r0, map.depth[k] - cut);
    }
  }
  s.raw = BezierNetwork(lifted);
  s.smooth = BezierNetwork(smoothed(lifted, passes));
  s.remaining = BezierNetwork(remaining);
  return s;
}

// The runs of a half-step path inside the layer's region, sampled every `ds` mm along its parameter polyline, each
// run ending on the boundary (bisection between the last sample in and the first out).
std::vector<std::vector<Eigen::Vector2d>> clip_along(const SurfacePath& path, const LayerSurface& s, double ds) {
  std::vector<Eigen::Vector2d> samples;
  for (std::size_t i = 0; i + 1 < path.uv.size(); ++i) {
    const int pieces = std::max(1, static_cast<int>(std::ceil((path.points[i + 1] - path.points[i]).norm() / ds)));
    for (int k = 0; k < pieces; ++k) samples.push_back(path.uv[i] + (path.uv[i + 1] - path.uv[i]) * (double(k) / pieces));
  }
  if (!path.uv.empty()) samples.push_back(path.uv.back());
  auto boundary = [&](Eigen::Vector2d in, Eigen::Vector2d out) {
    for (int it = 0; it < 30; ++it) {
      const Eigen::Vector2d m = 0.5 * (in + out);
      (s.inside(m) ? in : out) = m;
    }
    return in;
  };
  std::vector<std::vector<Eigen::Vector2d>> runs;
  std::vector<Eigen::Vector2d> run;
  bool previous = false;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const bool in = s.inside(samples[i]);
    if (in && !previous && i > 0) run.push_back(boundary(samples[i], samples[i - 1]));
    if (in) run.push_back(samples[i]);
    if (!in && previous) {
      run.push_back(boundary(samples[i - 1], samples[i]));
      runs.push_back(std::move(run));
      run.clear();
    }
    previous = in;
  }
  if (run.size() >= 2) runs.push_back(std::move(run));
  runs.erase(std::remove_if(runs.begin(), runs.end(), [](const auto& r) { return r.size() < 2; }), runs.end());
  return runs;
}

// The paper's loop heuristic across paths: where the parallels focus (a deep bowl, positive Gaussian curvature) a
// later path of the layer can cross an earlier one after their loops are cut; its crossing segments are dropped and
// it is split there, so no two beads of a layer cross. Works in the plane across `normal`. Returns the segments cut.
std::size_t cut_crossings(std::vector<WeldPath>* paths, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d e1 =
      (std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(normal).normalized();
  const Eigen::Vector3d e2 = normal.cross(e1);
  auto flat = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d(x.dot(e1), x.dot(e2)); };
  auto orient = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    return (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
  };
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> accepted;
  std::vector<WeldPath> out;
  std::size_t cut = 0;
  for (WeldPath& path : *paths) {
    WeldPath piece = path;
    piece.points.clear(), piece.normals.clear();
    std::vector<WeldPath> pieces;
    for (std::size_t i = 0; i < path.points.size(); ++i) {
      bool crosses = false;
      if (!piece.points.empty()) {
        const Eigen::Vector2d a = flat(piece.points.back()), b = flat(path.points[i]);
        for (const auto& [c, d] : accepted) {
          if (orient(a, b, c) * orient(a, b, d) < 0.0 && orient(c, d, a) * orient(c, d, b) < 0.0) crosses = true;
          if (crosses) break;
        }
      }
      if (crosses) {
        ++cut;
        if (piece.points.size() >= 2) pieces.push_back(piece);
        piece.points.clear(), piece.normals.clear();
      }
      piece.points.push_back(path.points[i]), piece.normals.push_back(path.normals[i]);
    }
    if (piece.points.size() >= 2) pieces.push_back(piece);
    for (WeldPath& q : pieces) {
      for (std::size_t i = 0; i + 1 < q.points.size(); ++i) accepted.emplace_back(flat(q.points[i]), flat(q.points[i + 1]));
      out.push_back(std::move(q));
    }
  }
  *paths = std::move(out);
  return cut;
}

}  // namespace

LayerPlan plan_layer(const BezierNetwork& eroded, const DamageMap& map, int region, int k,
                     const WeldLayerOptions& options) {
  LayerPlan plan;
  const DamageRegion& reg = map.regions[static_cast<std::size_t>(region - 1)];
  const double dc = options.bead_spacing_mm, level = (k - 1) * options.layer_height_mm, cut = level + map.threshold_mm;
  for (int r = reg.row_min; r <= reg.row_max; ++r) {
    for (int c = reg.col_min; c <= reg.col_max; ++c) {
      const std::size_t n = static_cast<std::size_t>(r * map.cols + c);
      if (map.label[n] == region && map.depth[n] > cut) plan.region_nodes.push_back(eroded.position(c, r) + level * map.outward[n]);
    }
  }
  if (plan.region_nodes.empty()) return plan;
  // Every layer of a region works over the region's (layer 1's) box and from the same start line, so that layer k's
  // half-step paths are layer 1's family lifted and the odd/even interleaving holds from one layer to the next.
  const double su = eroded.derivative(reg.deepest_col, reg.deepest_row, 1, 0).norm();
  const double sv = eroded.derivative(reg.deepest_col, reg.deepest_row, 0, 1).norm();
  const int mr = static_cast<int>(std::ceil(dc / sv)) + 2, mc = static_cast<int>(std::ceil(dc / su)) + 2;
  const int r0 = std::max(0, reg.row_min - mr), r1 = std::min(map.rows - 1, reg.row_max + mr);
  const int c0 = std::max(0, reg.col_min - mc), c1 = std::min(map.cols - 1, reg.col_max + mc);
  // n binomial passes smooth like a Gaussian of sigma sqrt(n / 2) nodes: dc / 4 for the curvature of Eq. (1) and (5).
  const double h = std::min(su, sv), auto_passes = std::ceil(2.0 * std::pow(dc / (4.0 * h), 2));
  const int passes = options.smoothing_passes >= 0 ? options.smoothing_passes
                                                   : static_cast<int>(std::clamp(auto_passes, 3.0, 50.0));
  const LayerSurface s = layer_surface(eroded, map, region, level, cut, r0, r1, c0, c1, passes);
  const double height_mm = (r1 - r0) * sv, estimate = std::ceil(height_mm / (0.5 * dc)) * 2.0 + 10.0;
  if (estimate > kMaxHalfStepPaths) {
    throw Error("weld layers: region " + std::to_string(region) + " needs about " + std::to_string(int(estimate)) +
                " half-step paths (limit kMaxHalfStepPaths " + std::to_string(kMaxHalfStepPaths) +
                "): the bead spacing is too small for the area");
  }
  ParallelPathOptions po;
  po.spacing_mm = 0.5 * dc;
  po.torch_distance_mm = 0.0;  // planned on the surface: g = dc / 2 (not Eq. 5 at the torch: its offset surface folds)
  po.chord_error_mm = options.chord_error_mm;
  po.max_step_mm = options.max_step_mm > 0.0 ? options.max_step_mm : 2.0 * dc;
  const ParameterDomain d = s.smooth.domain();
  const Eigen::Vector2d centre(0.5 * d.u_max, 0.5 * d.v_max);
  const Eigen::Vector3d out = map.outward[static_cast<std::size_t>(reg.deepest_row * map.cols + reg.deepest_col)];
  po.normal_sign = s.smooth.normal(centre.x(), centre.y()).dot(out) >= 0.0 ? 1 : -1;
  po.side = 1;
  po.max_paths = static_cast<int>(estimate);
  // Layer 1's paths (half-step paths 1, 3, ...) centred over the rows of the region's nodes: the outermost nodes are
  // at most dc / 2 beyond the outermost paths; half-step path 0 (the start line) dc / 2 before the first.
  const double extent = (reg.row_max - reg.row_min) * sv;
  const double n_paths = std::floor(extent / dc) + 1.0;
  const double first = 0.5 * (extent - (n_paths - 1.0) * dc);
  // At the grid's border the start line would lie off the grid: start with layer 1's first path instead.
  double v_start = (reg.row_min - r0) + (first - 0.5 * dc) / sv;
  const std::size_t shift = v_start < 0.0 ? 1 : 0;
  if (shift == 1) v_start = std::max(0.0, v_start + 0.5 * dc / sv);
  const ParallelPathResult half = parallel_paths(s.smooth, {{d.u_min, v_start}, {d.u_max, v_start}}, po);
  plan.half_step_paths = half.paths.size();
  plan.loops_removed = half.loops_removed;
  plan.newton_offsets = half.newton_offsets;
  // The family crosses the region once. After it has left (two half-step lines in a row with no point inside), later
  // lines are parallels turning back over the region in a bowl (their loops cut): they would lay beads over beads.
  std::size_t lines = half.paths.size();
  bool seen = false;
  int empty = 0;
  for (std::size_t j = 0; j < half.paths.size() && lines == half.paths.size(); ++j) {
    const std::vector<Eigen::Vector2d>& uv = half.paths[j].uv;
    bool any = false;
    for (std::size_t i = 0; i < uv.size() && !any; ++i) {
      any = s.inside(uv[i]) || (i + 1 < uv.size() && s.inside(0.5 * (uv[i] + uv[i + 1])));
    }
    empty = any ? 0 : empty + 1;
    seen = seen || any;
    if (seen && empty >= 2) lines = j + 1;
  }
  plan.lines_turned_back = half.paths.size() - lines;
  plan.max_paths_reached = half.termination == "max_paths reached" && lines == half.paths.size();
  for (std::size_t j = 0; j + 1 < lines; ++j) {
    const double e = spacing_error_pct_max(s.smooth, half.paths[j], half.paths[j + 1],
                                           [&](const Eigen::Vector2d& uv) { return s.inside(uv); });
    plan.spacing_error_pct_max = std::max(plan.spacing_error_pct_max, e);
  }
  const double ds = std::min(0.25 * dc, 0.5 * std::min(su, sv));
  const double bead_width = options.bead_width_mm > 0.0 ? options.bead_width_mm : dc;
  ParallelPathOptions step = po;
  for (std::size_t j = (k % 2 == 1) ? 1 - shift : shift; j < lines; j += 2) {
    for (std::vector<Eigen::Vector2d>& run : clip_along(half.paths[j], s, ds)) {
      std::vector<Eigen::Vector3d> points;
      for (const Eigen::Vector2d& uv : run) points.push_back(s.raw.position(uv.x(), uv.y()));
      plan.cusps_removed += conform::remove_cusps(&points, &run);
      if (run.size() < 2) continue;
      SurfacePath stepped = step_along(s.raw, run, step, &plan.chord_error_mm_max);
      plan.cusps_removed += conform::remove_cusps(&stepped.points, &stepped.uv);
      if (stepped.points.size() < 2) continue;
      WeldPath path;
      path.layer = k;
      path.region = region;
      path.bead_width_mm = bead_width;
      path.line = static_cast<int>(j);
      path.points = stepped.points;
      for (const Eigen::Vector2d& uv : stepped.uv) path.normals.push_back(po.normal_sign * s.smooth.normal(uv.x(), uv.y()));
      plan.paths.push_back(std::move(path));
    }
  }
  plan.crossings_cut = cut_crossings(&plan.paths, out);
  return plan;
}

}  // namespace conform::detail
