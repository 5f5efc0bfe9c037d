// The damaged area's boundary on the generated eroded blade (120 x 80 mm, 41 x 61 grid, craters of 15 mm / 2 mm and
// 8 mm / 1 mm, noise 0.01 mm): recursive subdivision of patch pairs (toolpath/intersection/surface_intersection.h) against a peer,
// the sampled depth field (depth of the eroded surface below the offset reference on a parameter grid as fine as the
// tolerance, rim points by linear interpolation where it changes sign: marching squares without the squares).
// Prints time and the rim's worst distance from the analytic rho_t for both, then the whole weld-layers plan.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_timer.h"
#include "conform/datasets/eroded.h"
#include "conform/fitting/bezier_network.h"
#include "conform/toolpath/intersection/surface_intersection.h"
#include "conform/toolpath/weld/weld_layers.h"

using namespace conform;

namespace {

constexpr double kThreshold = 0.06;  // mm, 6 x the noise

double rim_radius(const Crater& c) { return c.radius_mm * std::sqrt(1.0 - std::cbrt(kThreshold / c.depth_mm)); }

// Worst |rho - rho_t| over points, each judged against its nearest crater.
double worst_rim_error(const ErodedOptions& o, const std::vector<Eigen::Vector3d>& points) {
  double worst = 0.0;
  for (const Eigen::Vector3d& p : points) {
    double best = 1e9;
    for (const Crater& c : o.craters) {
      const double e = std::abs(std::hypot(p.x() - c.x_mm, p.y() - c.y_mm) - rim_radius(c));
      best = std::min(best, e);
    }
    worst = std::max(worst, best);
  }
  return worst;
}

std::vector<Eigen::Vector3d> sampled_rims(const BezierNetwork& eroded, const BezierNetwork& offset, double step) {
  const ParameterDomain d = eroded.domain();
  const int nu = static_cast<int>((d.u_max - d.u_min) / step) + 1, nv = static_cast<int>((d.v_max - d.v_min) / step) + 1;
  std::vector<double> depth(static_cast<std::size_t>(nu * nv));
  for (int j = 0; j < nv; ++j) {
    double u_ref = 0.0, v_ref = j * step;
    for (int i = 0; i < nu; ++i) {
      const Eigen::Vector3d p = eroded.position(i * step, j * step);
      u_ref = i * step;  // the grids share their layout: the same parameters start Newton next to the answer
      project_to_surface(offset, p, &u_ref, &v_ref);
      depth[static_cast<std::size_t>(j * nu + i)] = (p - offset.position(u_ref, v_ref)).dot(offset.normal(u_ref, v_ref));
    }
  }
  std::vector<Eigen::Vector3d> rim;
  auto edge = [&](int i0, int j0, int i1, int j1) {
    const double a = depth[static_cast<std::size_t>(j0 * nu + i0)], b = depth[static_cast<std::size_t>(j1 * nu + i1)];
    if ((a < 0.0) == (b < 0.0)) return;
    const double t = a / (a - b);
    rim.push_back(eroded.position((i0 + t * (i1 - i0)) * step, (j0 + t * (j1 - j0)) * step));
  };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      if (i + 1 < nu) edge(i, j, i + 1, j);
      if (j + 1 < nv) edge(i, j, i, j + 1);
    }
  }
  return rim;
}

}  // namespace

void run(double noise_mm) {
  ErodedOptions o;
  o.craters = {Crater{0.0, 0.0, 15.0, 2.0}, Crater{35.0, 10.0, 8.0, 1.0}};
  o.noise_mm = noise_mm;
  const ErodedScan scan = generate_eroded(o);
  const BezierNetwork eroded(SurfaceGrid{scan.rows, scan.cols, scan.eroded});
  const BezierNetwork reference(SurfaceGrid{scan.rows, scan.cols, scan.reference});
  SurfaceGrid offset_grid{scan.rows, scan.cols, {}};
  for (int r = 0; r < scan.rows; ++r) {
    for (int c = 0; c < scan.cols; ++c) {
      offset_grid.points.push_back(reference.position(c, r) - kThreshold * reference.normal(c, r));
    }
  }
  const BezierNetwork offset(offset_grid);
  std::printf("\nnoise %.3f mm: boundary of the damage, threshold %.2f mm (analytic rims %.4f and %.4f mm)\n",
              noise_mm, kThreshold, rim_radius(o.craters[0]), rim_radius(o.craters[1]));
  std::printf("%-10s %-28s %10s %8s %14s\n", "tolerance", "method", "time s", "points", "rim error mm");
  for (const double tolerance : {0.3, 0.1}) {
    IntersectionResult cut;
    IntersectionOptions io;
    io.tolerance_mm = tolerance;
    const double t_sub = bench::best_cpu_seconds(3, [&] { cut = intersect_surfaces(eroded, offset, io); });
    std::vector<Eigen::Vector3d> sub_points;
    for (const IntersectionCurve& c : cut.curves) {
      for (const IntersectionPoint& p : c.points) sub_points.push_back(p.position);
    }
    std::vector<Eigen::Vector3d> sampled;
    const double step = tolerance / 2.0;  // grid units are 2 mm: a step of tolerance mm
    const double t_peer = bench::best_cpu_seconds(1, [&] { sampled = sampled_rims(eroded, offset, step); });
    std::printf("%-10.2f %-28s %10.4f %8zu %14.4f\n", tolerance, "subdivision + Newton", t_sub, sub_points.size(),
                worst_rim_error(o, sub_points));
    std::printf("%-10.2f %-28s %10.4f %8zu %14.4f\n", tolerance, "sampled depth field (peer)", t_peer, sampled.size(),
                worst_rim_error(o, sampled));
    std::printf("%-10.2f speed-up of subdivision: %.1fx, %zu curves (%zu closed)\n", tolerance, t_peer / t_sub,
                cut.curves.size(), static_cast<std::size_t>(std::count_if(cut.curves.begin(), cut.curves.end(),
                                                                          [](const auto& c) { return c.closed; })));
  }
  WeldLayerOptions w;
  w.bead_spacing_mm = 3.0;
  w.layer_height_mm = 1.0;
  w.chord_error_mm = 0.05;
  w.torch_distance_mm = 10.0;
  WeldLayerResult plan;
  const double t_plan = bench::best_cpu_seconds(3, [&] { plan = plan_weld_layers(eroded, reference, w); });
  std::printf("weld-layers plan (dc 3, cd 1, delta 0.05, w 10 mm): %.4f s, %d layers, %zu paths, %.1f mm, spacing "
              "error %.2f %%, chord error %.4f mm, coverage by layer",
              t_plan, plan.layers, plan.paths.size(), plan.total_length_mm, plan.spacing_error_pct_max,
              plan.chord_error_mm_max);
  for (double pct : plan.coverage_pct) std::printf(" %.1f %%", pct);
  std::printf("\n");
}

// Top-level candidate pairs of the intersection by a loop over all patch pairs (the peer: what the intersection did
// before its box tree) against the box tree's count, and the whole plan, for growing grids: 120 x 80 mm blade with
// craters of 15 mm / 2.5 mm, 8 mm / 1 mm (and one over the border), noise 0.01 mm; the reference grid may be finer.
std::size_t all_pairs_overlaps(const BezierNetwork& a, const BezierNetwork& b) {
  std::size_t hits = 0;
  for (int ra = 0; ra < a.patch_rows(); ++ra) {
    for (int ca = 0; ca < a.patch_cols(); ++ca) {
      const Eigen::AlignedBox3d box = a.patch(ra, ca).bounds();
      for (int rb = 0; rb < b.patch_rows(); ++rb) {
        for (int cb = 0; cb < b.patch_cols(); ++cb) hits += box.intersects(b.patch(rb, cb).bounds());
      }
    }
  }
  return hits;
}

void grid_sizes() {
  std::printf("\ngrid size vs time: weld-layers plan (dc 3, cd 1, delta 0.05, w 2 mm), CPU s, best of 1\n");
  std::printf("%-12s %-12s %10s %10s %10s %8s %8s %14s\n", "eroded", "reference", "plan s", "all-pairs", "box pairs",
              "paths", "cover %", "status");
  const int sizes[][4] = {{41, 61, 41, 61}, {121, 181, 121, 181}, {201, 301, 201, 301}, {301, 301, 501, 501}};
  for (const auto& s : sizes) {
    ErodedOptions o;
    o.rows = s[0], o.cols = s[1];
    o.craters = {Crater{0.0, 0.0, 15.0, 2.5}, Crater{35.0, 10.0, 8.0, 1.0}, Crater{58.0, -30.0, 10.0, 1.5}};
    const ErodedScan e = generate_eroded(o);
    o.rows = s[2], o.cols = s[3];
    const ErodedScan r = generate_eroded(o);
    const BezierNetwork eroded(SurfaceGrid{e.rows, e.cols, e.eroded});
    const BezierNetwork reference(SurfaceGrid{r.rows, r.cols, r.reference});
    WeldLayerOptions w;
    w.bead_spacing_mm = 3.0, w.layer_height_mm = 1.0, w.chord_error_mm = 0.05, w.torch_distance_mm = 2.0;
    WeldLayerResult plan;
    const double t_plan = bench::best_cpu_seconds(1, [&] { plan = plan_weld_layers(eroded, reference, w); });
    double t_peer = -1.0;  // the quadratic peer only where it ends in reasonable time
    if (static_cast<double>(e.eroded.size()) * static_cast<double>(r.reference.size()) < 1e9) {
      t_peer = bench::best_cpu_seconds(1, [&] { (void)all_pairs_overlaps(eroded, reference); });
    }
    char grid_e[32], grid_r[32];
    std::snprintf(grid_e, sizeof grid_e, "%dx%d", s[0], s[1]);
    std::snprintf(grid_r, sizeof grid_r, "%dx%d", s[2], s[3]);
    std::printf("%-12s %-12s %10.3f %10.3f %10zu %8zu %8.2f %14s\n", grid_e, grid_r, t_plan, t_peer, plan.box_pairs,
                plan.paths.size(), plan.damage_coverage_pct, plan.ok ? "ok" : "not ok");
    if (!plan.ok) std::printf("  %s\n", plan.termination.c_str());
  }
  std::printf("(all-pairs: only the top-level box tests of the old intersection loop; -1: skipped, > 1e9 pairs)\n");
}

int main() {
  run(0.01);
  run(0.0);
  grid_sizes();
  return 0;
}
