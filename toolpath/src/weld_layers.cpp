#include "conform/toolpath/weld_layers.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/toolpath/parallel_paths.h"

namespace conform {
namespace {

constexpr double kNoiseFactor = 6.0;        // default depth threshold in noise sigmas: clear of the noise's tails
constexpr double kMinThresholdMm = 0.01;    // default threshold floor for noise-free data

// Signed distance of points to the reference surface along its normal r_u x r_v, by closest point (Newton) from the
// nearest of a dense set of samples.
class DistanceToReference {
 public:
  explicit DistanceToReference(const BezierNetwork& reference) : reference_(reference) {
    const ParameterDomain d = reference.domain();
    for (double v = d.v_min; v <= d.v_max + 1e-9; v += 0.25) {
      for (double u = d.u_min; u <= d.u_max + 1e-9; u += 0.25) {
        samples_.push_back(reference.position(u, v));
        params_.emplace_back(u, v);
      }
    }
    tree_ = std::make_unique<KdTree>(samples_);
  }
  double operator()(const Eigen::Vector3d& p) const {
    const int k = tree_->nearest(p.cast<float>());
    double u = params_[static_cast<std::size_t>(k)].x(), v = params_[static_cast<std::size_t>(k)].y();
    project_to_surface(reference_, p, &u, &v);
    return (p - reference_.position(u, v)).dot(reference_.normal(u, v));
  }

 private:
  const BezierNetwork& reference_;
  std::vector<Eigen::Vector3d> samples_;
  std::vector<Eigen::Vector2d> params_;
  std::unique_ptr<KdTree> tree_;
};

double median(std::vector<double> x) {
  if (x.empty()) return 0.0;
  const auto mid = x.begin() + static_cast<long>(x.size() / 2);
  std::nth_element(x.begin(), mid, x.end());
  return *mid;
}

// The reference grid moved by `offset` mm along `sign` (r_u x r_v).
BezierNetwork offset_network(const BezierNetwork& reference, double offset) {
  SurfaceGrid grid;
  grid.rows = reference.patch_rows() + 1;
  grid.cols = reference.patch_cols() + 1;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      grid.points.push_back(reference.position(c, r) + offset * reference.normal(c, r));
    }
  }
  return BezierNetwork(grid);
}

// The grid of the network's nodes smoothed by `passes` binomial [1 2 1] / 4 passes along rows and columns (ends
// kept): the paths' Eq. (5) uses curvature, a second derivative that the measurement noise would dominate.
BezierNetwork smoothed_network(const BezierNetwork& network, int passes) {
  SurfaceGrid grid;
  grid.rows = network.patch_rows() + 1;
  grid.cols = network.patch_cols() + 1;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) grid.points.push_back(network.position(c, r));
  }
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
  return BezierNetwork(grid);
}

struct Clipper {
  const BezierNetwork& eroded;
  const DistanceToReference& distance;
  const std::vector<std::vector<Eigen::Vector2d>>& rims;
  double inward;  // +1 / -1: the side of the reference's normal where craters go

  bool in_rims(const Eigen::Vector2d& uv) const {
    for (const auto& polygon : rims) {
      if (polygon_contains(polygon, uv)) return true;
    }
    return false;
  }
  double depth(const Eigen::Vector2d& uv) const { return inward * distance(eroded.position(uv.x(), uv.y())); }
  bool inside(const Eigen::Vector2d& uv, double level) const { return in_rims(uv) && (level <= 0.0 || depth(uv) > level); }
  // The boundary crossing between an inside point a and an outside point b (bisection on the parameter segment).
  Eigen::Vector2d crossing(Eigen::Vector2d a, Eigen::Vector2d b, double level) const {
    for (int it = 0; it < 14; ++it) {
      const Eigen::Vector2d m = 0.5 * (a + b);
      (inside(m, level) ? a : b) = m;
    }
    return a;
  }
};

}  // namespace

bool WeldLayerOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(bead_spacing_mm)) return fail("bead spacing must be > 0 mm");
  if (!positive(layer_height_mm)) return fail("layer height must be > 0 mm");
  if (!positive(chord_error_mm)) return fail("chord error must be > 0 mm");
  if (!(torch_distance_mm >= 0.0) || !std::isfinite(torch_distance_mm)) return fail("torch distance must be >= 0 mm");
  if (layers < 0 || layers > 1000) return fail("layers must be in [0, 1000] (0: as many as the depth needs)");
  if (!std::isfinite(depth_threshold_mm)) return fail("depth threshold must be finite");
  if (!(intersection_tolerance_mm >= 0.0)) return fail("intersection tolerance must be >= 0 mm");
  if (!(max_step_mm >= 0.0)) return fail("max step must be >= 0 mm");
  if (smoothing_passes < 0 || smoothing_passes > 50) return fail("smoothing passes must be in [0, 50]");
  return true;
}

double WeldPath::length_mm() const {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

namespace {

// Step 1: noise, inward side and depth from the eroded grid points.
void measure_depths(const BezierNetwork& eroded, const DistanceToReference& distance, WeldLayerResult* result,
                    double* inward) {
  std::vector<double> s;
  for (int r = 0; r <= eroded.patch_rows(); ++r) {
    for (int c = 0; c <= eroded.patch_cols(); ++c) s.push_back(distance(eroded.position(c, r)));
  }
  const double m = median(s);
  std::vector<double> deviation;
  for (double x : s) deviation.push_back(std::abs(x - m));
  result->noise_mm = 1.4826 * median(deviation);
  const double extreme = *std::max_element(s.begin(), s.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  *inward = extreme < 0.0 ? -1.0 : 1.0;
  result->max_depth_mm = std::abs(extreme);
}

}  // namespace

namespace {

// Step 4 for one half-step path and one layer: the runs of points inside the layer's region, with the crossings.
std::vector<std::vector<Eigen::Vector2d>> clip(const SurfacePath& path, const std::vector<bool>& in_rims,
                                               const std::vector<double>& depth, double level,
                                               const Clipper& clipper) {
  std::vector<std::vector<Eigen::Vector2d>> runs;
  std::vector<Eigen::Vector2d> run;
  auto inside = [&](std::size_t i) { return in_rims[i] && (level <= 0.0 || depth[i] > level); };
  for (std::size_t i = 0; i < path.uv.size(); ++i) {
    const bool in = inside(i);
    if (in && run.empty() && i > 0) run.push_back(clipper.crossing(path.uv[i], path.uv[i - 1], level));
    if (in) run.push_back(path.uv[i]);
    if (!in && !run.empty()) {
      run.push_back(clipper.crossing(path.uv[i - 1], path.uv[i], level));
      runs.push_back(std::move(run));
      run.clear();
    }
  }
  if (!run.empty()) runs.push_back(std::move(run));
  runs.erase(std::remove_if(runs.begin(), runs.end(), [](const auto& r) { return r.size() < 2; }), runs.end());
  return runs;
}

// % of the layer's region (samples deeper than its level) within 0.55 of the local bead spacing (2 g of the half-step
// path, Eq. 5) of its paths' surface points: each bead covers half the spacing to either side, plus 10 %.
double coverage_pct(const std::vector<Eigen::Vector3d>& samples, const std::vector<double>& sample_depth, double level,
                    const std::vector<Eigen::Vector3d>& path_points, const std::vector<double>& spacing) {
  if (path_points.empty()) return 0.0;
  const KdTree tree(path_points);
  std::size_t region = 0, covered = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (level > 0.0 && !(sample_depth[i] > level)) continue;
    ++region;
    float d2 = 0.0f;
    const int k = tree.nearest(samples[i].cast<float>(), &d2);
    if (std::sqrt(static_cast<double>(d2)) <= 0.55 * spacing[static_cast<std::size_t>(k)]) ++covered;
  }
  return region == 0 ? 100.0 : 100.0 * static_cast<double>(covered) / static_cast<double>(region);
}

// Step 2: the closed rims of the eroded surface against the reference offset inward by the threshold; false (with
// the reason in result->termination) when there are none.
bool find_rims(const BezierNetwork& eroded, const BezierNetwork& reference, double inward,
               const WeldLayerOptions& options, WeldLayerResult* result,
               std::vector<std::vector<Eigen::Vector2d>>* polygons) {
  IntersectionOptions io;
  io.tolerance_mm = options.intersection_tolerance_mm > 0.0 ? options.intersection_tolerance_mm
                                                            : options.bead_spacing_mm / 10.0;
  const IntersectionResult cut =
      intersect_surfaces(eroded, offset_network(reference, inward * result->depth_threshold_mm), io);
  if (!cut.ok) {
    result->termination = "boundary of the damage: " + cut.termination;
    return false;
  }
  for (const IntersectionCurve& c : cut.curves) {
    if (c.closed) {
      result->rims.push_back(c);
      polygons->push_back(parameter_polygon_a(c));
    } else {
      ++result->open_curves;
    }
  }
  if (cut.curves.empty()) {
    result->termination = "no damage found: the eroded surface does not reach " +
                          format_fixed(result->depth_threshold_mm, 4) + " mm below the reference";
    return false;
  }
  if (result->rims.empty()) {
    result->termination = "the damaged area's boundary is not closed (it runs off the measured grid)";
    return false;
  }
  return true;
}

ParameterDomain bounding_box(const std::vector<std::vector<Eigen::Vector2d>>& polygons) {
  ParameterDomain box{1e300, -1e300, 1e300, -1e300};
  for (const auto& polygon : polygons) {
    for (const Eigen::Vector2d& uv : polygon) {
      box.u_min = std::min(box.u_min, uv.x()), box.u_max = std::max(box.u_max, uv.x());
      box.v_min = std::min(box.v_min, uv.y()), box.v_max = std::max(box.v_max, uv.y());
    }
  }
  return box;
}

// Step 3: the half-step paths on the smoothed eroded surface, from the iso-line v = const just below the rims'
// box towards +v (Eq. 8-9 with direction +u, side +1), until a path leaves the box.
ParallelPathResult half_step_paths(const BezierNetwork& smooth, const ParameterDomain& box, double outward,
                                   const WeldLayerOptions& options) {
  const ParameterDomain d = smooth.domain();
  const double margin = 0.25;  // grid units: the paths start just outside the rims and reach past them sideways
  const double u0 = std::max(d.u_min, box.u_min - 4 * margin), u1 = std::min(d.u_max, box.u_max + 4 * margin);
  const double v0 = std::max(d.v_min, box.v_min - margin);
  ParallelPathOptions po;
  po.spacing_mm = 0.5 * options.bead_spacing_mm;
  po.torch_distance_mm = options.torch_distance_mm;
  po.chord_error_mm = options.chord_error_mm;
  po.max_step_mm = options.max_step_mm > 0.0 ? options.max_step_mm : 2.0 * options.bead_spacing_mm;
  po.normal_sign = outward > 0.0 ? 1 : -1;
  po.side = 1;
  po.region = {u0, u1, v0, box.v_max + margin};
  return parallel_paths(smooth, {{u0, v0}, {u1, v0}}, po);
}

// Points inside the rims at about dc / 4 over their box, with their depth: what the coverage figure counts.
struct CoverageSamples {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> depth;
};

CoverageSamples coverage_samples(const BezierNetwork& eroded, const ParameterDomain& box, const Clipper& clipper,
                                 double dc) {
  const double um = 0.5 * (box.u_min + box.u_max), vm = 0.5 * (box.v_min + box.v_max);
  const double du = 0.25 * dc / eroded.derivative(um, vm, 1, 0).norm();
  const double dv = 0.25 * dc / eroded.derivative(um, vm, 0, 1).norm();
  CoverageSamples s;
  for (double v = box.v_min; v <= box.v_max; v += dv) {
    for (double u = box.u_min; u <= box.u_max; u += du) {
      if (!clipper.in_rims({u, v})) continue;
      s.points.push_back(eroded.position(u, v));
      s.depth.push_back(clipper.depth({u, v}));
    }
  }
  return s;
}

// Step 4 for layer k: the odd half-step paths (1, 3, ...) for odd layers, the even ones for even layers, clipped,
// lifted by (k - 1) cd; appends them and the layer's coverage to the result.
void add_layer(int k, const BezierNetwork& eroded, const ParallelPathResult& half,
               const std::vector<std::vector<bool>>& in_rims, const std::vector<std::vector<double>>& depth,
               const Clipper& clipper, double outward, const CoverageSamples& samples,
               const WeldLayerOptions& options, WeldLayerResult* result) {
  const double level = (k - 1) * options.layer_height_mm;
  int number = 0;
  std::vector<Eigen::Vector3d> on_surface;  // densified, for the coverage figure
  std::vector<double> spacing;
  for (std::size_t j = (k % 2 == 1) ? 0 : 1; j < half.paths.size(); j += 2) {
    const std::vector<double>& g = half.paths[j].spacing_mm;
    const double bead = 2.0 * *std::max_element(g.begin(), g.end());
    for (const auto& run : clip(half.paths[j], in_rims[j], depth[j], level, clipper)) {
      WeldPath path;
      path.layer = k;
      path.path = ++number;
      for (const Eigen::Vector2d& uv : run) {
        const Eigen::Vector3d p = eroded.position(uv.x(), uv.y());
        const Eigen::Vector3d n = outward * eroded.normal(uv.x(), uv.y());
        if (!path.points.empty()) {
          const Eigen::Vector3d prev = on_surface.back();
          for (int s = 1; s < 8; ++s) on_surface.push_back(prev + (p - prev) * (s / 8.0)), spacing.push_back(bead);
        }
        on_surface.push_back(p);
        spacing.push_back(bead);
        path.points.push_back(p + level * n);
        path.normals.push_back(n);
      }
      result->total_length_mm += path.length_mm();
      result->paths.push_back(std::move(path));
    }
  }
  const double covered = coverage_pct(samples.points, samples.depth, level, on_surface, spacing);
  result->coverage_pct.push_back(covered);
  result->coverage_pct_min = std::min(result->coverage_pct_min, covered);
}

}  // namespace

WeldLayerResult plan_weld_layers(const BezierNetwork& eroded, const BezierNetwork& reference,
                                 const WeldLayerOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error("weld layers: " + error);
  WeldLayerResult result;
  const DistanceToReference distance(reference);
  double inward = 1.0;
  measure_depths(eroded, distance, &result, &inward);
  result.threshold_estimated = options.depth_threshold_mm < 0.0;
  result.depth_threshold_mm = result.threshold_estimated ? std::max(kNoiseFactor * result.noise_mm, kMinThresholdMm)
                                                         : options.depth_threshold_mm;
  std::vector<std::vector<Eigen::Vector2d>> polygons;
  if (!find_rims(eroded, reference, inward, options, &result, &polygons)) return result;
  result.layers = options.layers > 0
                      ? options.layers
                      : std::max(1, static_cast<int>(std::ceil(result.max_depth_mm / options.layer_height_mm)));
  const ParameterDomain box = bounding_box(polygons);
  const double um = 0.5 * (box.u_min + box.u_max), vm = 0.5 * (box.v_min + box.v_max);
  // The torch side: away from where the craters go (the reference's normal times -inward), seen on the eroded grid.
  double ur = um, vr = vm;
  project_to_surface(reference, eroded.position(um, vm), &ur, &vr);
  const double outward = eroded.normal(um, vm).dot(-inward * reference.normal(ur, vr)) >= 0.0 ? 1.0 : -1.0;
  const BezierNetwork smooth = smoothed_network(eroded, options.smoothing_passes);
  const ParallelPathResult half = half_step_paths(smooth, box, outward, options);
  result.half_step_paths = half.paths.size();
  result.loops_removed = half.loops_removed;
  result.newton_offsets = half.newton_offsets;
  result.chord_error_mm_max = half.chord_error_mm_max;
  const Clipper clipper{eroded, distance, polygons, inward};
  for (std::size_t j = 0; j + 1 < half.paths.size(); ++j) {
    const double e = spacing_error_pct_max(smooth, half.paths[j], half.paths[j + 1],
                                           [&](const Eigen::Vector2d& uv) { return clipper.in_rims(uv); });
    result.spacing_error_pct_max = std::max(result.spacing_error_pct_max, e);
  }
  std::vector<std::vector<bool>> in_rims(half.paths.size());
  std::vector<std::vector<double>> depth(half.paths.size());
  for (std::size_t j = 0; j < half.paths.size(); ++j) {
    for (const Eigen::Vector2d& uv : half.paths[j].uv) {
      in_rims[j].push_back(clipper.in_rims(uv));
      depth[j].push_back(in_rims[j].back() ? clipper.depth(uv) : 0.0);
    }
  }
  const CoverageSamples samples = coverage_samples(eroded, box, clipper, options.bead_spacing_mm);
  result.coverage_pct_min = 100.0;
  for (int k = 1; k <= result.layers; ++k) {
    add_layer(k, eroded, half, in_rims, depth, clipper, outward, samples, options, &result);
  }
  result.ok = true;
  result.termination = "planned";
  return result;
}

}  // namespace conform
