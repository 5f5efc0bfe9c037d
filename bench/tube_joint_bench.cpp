// `conform tube-joint` at the size: a leg scan of about 1,000,000 triangles and a stub scan of about
// 300,000 (R 1000 mm leg, 500 mm stub with a 25 mm wall, pitch 45 deg, offset 100 mm; ovality 1% of D, peaking 3 mm,
// bumps, 0.2 mm noise). Times (best of 3, wall clock): the mesh intersection (grid + exact triangle pairs + welding +
// graph check) and the whole in-memory pipeline (pose, intersection, ordering, resampling, refinement, normals,
// tool paths), with 1 thread and with all threads. Then the accuracy against the generator's ground truth and the
// gap a nominal-cylinder cut would leave. No peer: CGAL (the usual one) is GPL.
// Targets of the issue: intersection < 0.7 s, pipeline < 2 s.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <omp.h>

#include "bench_timer.h"
#include "conform/core/constants.h"
#include "conform/datasets/tube_surface.h"
#include "conform/pipelines/generate/generate_tube_joint.h"
#include "conform/pipelines/tube_joint/tube_joint.h"
#include "conform/toolpath/intersection/intersection_graph.h"
#include "conform/toolpath/saddle/saddle_curve.h"

using conform::kPi;

namespace {

using conform::bench::best_seconds;

}  // namespace

int main() {
  using namespace conform;
  TubeJointSpec spec;
  spec.pitch_rad = kPi / 4;
  spec.offset_mm = 100.0;
  spec.protrusion_mm = automatic_protrusion(spec.pitch_rad, 1000.0, 500.0, 100.0);
  TubeJointOptions o;
  o.T_L_S = T_L_S(spec);
  o.protrusion_mm = spec.protrusion_mm;
  o.leg.radius_mm = 1000.0;
  o.stub.radius_mm = 475.0;
  o.leg.vertex_count = 500000;
  o.stub.vertex_count = 150000;
  o.leg.ovality_mm = 0.01 * 2000.0 / 4;
  o.stub.ovality_mm = 0.01 * 950.0 / 4;
  o.stub.ovality_azimuth_rad = 0.9;
  for (TubeOptions* t : {&o.leg, &o.stub}) {
    t->seam_height_mm = 3.0;
    t->seam_width_mm = 150.0;
    t->noise_mm = 0.2;
  }
  o.leg.seam_azimuth_rad = 15.0 * kPi / 180;
  o.stub.seam_azimuth_rad = 100.0 * kPi / 180;
  o.leg.bumps.push_back({-10.0 * kPi / 180, 150.0, 2.0, 80.0});
  o.stub.bumps.push_back({200.0 * kPi / 180, 300.0, 2.0, 60.0});
  o.leg.seed = 1;
  o.stub.seed = 2;
  std::printf("generating ...\n");
  const TubeJointScans scans = generate_tube_joint(o);
  std::printf(
      "leg %zu triangles (%zu vertices), stub %zu triangles (%zu vertices), edge ~%.2f mm\n", scans.leg_L.faces.size(),
      scans.leg_L.vertices.size(), scans.stub_S.faces.size(), scans.stub_S.vertices.size(),
      std::sqrt(4.0 * surface_area(scans.stub_S) / std::sqrt(3.0) / static_cast<double>(scans.stub_S.faces.size())));
  const Eigen::Isometry3d T_S_L = T_L_S(spec).inverse();
  Mesh leg_S = scans.leg_L;
  for (Eigen::Vector3d& v : leg_S.vertices) v = T_S_L * v;
  TubeJointSolveOptions solve;
  solve.sampling.step_rad = kPi / 180;
  solve.sampling.smoothing_rms_mm = 0.1;
  const int threads = omp_get_max_threads();
  for (const int t : {1, threads}) {
    omp_set_num_threads(t);
    std::size_t vertices = 0;
    const double intersection = best_seconds(3, [&] {
      const MeshIntersectionResult cut = intersect_meshes(leg_S, scans.stub_S);
      const IntersectionGraph graph = weld_segments(cut.segments);
      vertices = graph.vertices.size();
      if (!check_intersection_graph(graph).ok) std::printf("graph check failed\n");
    });
    TubeJointSolution solution;
    const double pipeline =
        best_seconds(3, [&] { solution = solve_tube_joint(scans.leg_L, scans.stub_S, T_S_L, solve); });
    std::printf("%d thread%s: intersection %.3f s (%zu curve vertices), whole pipeline %.3f s (%zu path points)%s\n", t,
                t == 1 ? " " : "s", intersection, vertices, pipeline, solution.path.points.size(),
                solution.ok ? "" : " FAILED");
  }
  // Accuracy, with and without the refinement onto the local surface fits.
  for (const int k_refine : {40, 0}) {
    solve.geometry.k_refine = k_refine;
    const TubeJointSolution solution = solve_tube_joint(scans.leg_L, scans.stub_S, T_S_L, solve);
    double to_truth = 0.0;
    double gap = 0.0;
    double sum = 0.0;
    for (const PathFrame& f : solution.frames) {
      const double d = distance_to_truth(scans.truth, f.point);
      to_truth = std::max(to_truth, d);
      sum += d * d;
      gap = std::max(gap, std::abs(leg_surface_distance(scans.truth, o.T_L_S, f.point)));
    }
    std::printf("path (%s): to truth max %.3f mm, RMS %.3f mm; gap to the real leg max %.3f mm\n",
                k_refine > 0 ? "refined, k 40" : "paper, not refined", to_truth,
                std::sqrt(sum / static_cast<double>(solution.frames.size())), gap);
  }
  SaddleGeometry geometry;
  geometry.leg_radius_mm = 1000.0;
  geometry.pipe_radius_mm = 475.0;
  geometry.pitch_rad = spec.pitch_rad;
  geometry.offset_mm = spec.offset_mm;
  const SaddleCurve nominal(geometry);
  double nominal_gap = 0.0;
  double nominal_truth = 0.0;
  for (int k = 0; k < 3600; ++k) {
    const double phi = 2.0 * kPi * k / 3600;
    const double z_S = (T_S_P(spec) * nominal.point(phi)).z();
    const TubeOptions& stub = scans.truth.stub;
    const Eigen::Vector3d edge =
        scans.truth.T_S_stub_tube * tube_surface_in_tube(stub, phi, z_S - 0.5 * stub.length_mm).point;
    nominal_gap = std::max(nominal_gap, std::abs(leg_surface_distance(scans.truth, o.T_L_S, edge)));
    nominal_truth = std::max(nominal_truth, std::abs(z_S - scans.truth.stub_z_mm[static_cast<std::size_t>(k)]));
  }
  std::printf(
      "nominal-cylinder cut on the real stub: gap to the real leg max %.3f mm (cut height off by up to "
      "%.3f mm along the stub)\n",
      nominal_gap, nominal_truth);
  return 0;
}
