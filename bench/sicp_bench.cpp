// Subdivision-ICP end to end at nose-cone scale: the default `generate nosecone` panel (about 10,000 contour points,
// 300,000 scan points, a 2,400-row trajectory) compensated in memory by S-ICP, by one rigid ICP and by the projection
// model, each from the raw scan to the compensated trajectory with re-estimated tool normals (thinning, the nominal
// surface's index, the registrations, the joint refinement, blending, normals). Files are not read: a separate line
// times run_sicp from the files the generator writes. The paper's implementation took 26 s for 10,000 points (2010
// hardware); the target here is under 0.5 s. Wall-clock, best of 3, with the time of each stage of the best run, and
// the error against the ground truth so that speed is never bought with accuracy.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench_timer.h"
#include "conform/compensation/trajectory_error.h"
#include "conform/datasets/panel.h"
#include "conform/pipelines/generate/generate_panel.h"
#include "conform/pipelines/sicp/sicp.h"

namespace {

using conform::bench::best_seconds;

conform::Trajectory path(const conform::PanelPath& p) { return {p.points, p.normals}; }

std::vector<Eigen::Vector3d> points_of(const conform::Cloud& cloud) {
  std::vector<Eigen::Vector3d> points;
  for (const pcl::PointXYZ& p : cloud.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

}  // namespace

int main() {
  conform::PanelOptions panel_options;
  panel_options.shape = conform::PanelShape::kNoseCone;
  const conform::PanelData panel = conform::generate_panel(panel_options);
  const std::vector<Eigen::Vector3d> scan = points_of(panel.scan);
  const conform::Trajectory nominal = path(panel.trajectory), truth = path(panel.truth);
  std::printf("nose cone: %zu contour points, %zu scan points, %zu trajectory rows, %zu surface faces\n",
              panel.contour.points.size(), scan.size(), nominal.points.size(), panel.surface.faces.size());
  std::printf("%-11s %9s %9s %9s %9s %9s %8s  stages (s)\n", "model", "time s", "path mean", "path max", "row mean",
              "row max", "vs 26 s");
  for (const conform::SicpModel model :
       {conform::SicpModel::kSicp, conform::SicpModel::kRigid, conform::SicpModel::kProjection}) {
    conform::SicpCompensationOptions options;
    options.model = model;
    std::map<std::string, double> stage_start, stage_seconds;
    options.sicp.progress = [&](std::string_view stage, double fraction) {
      const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
      if (fraction == 0.0) stage_start[std::string(stage)] = now;
      if (fraction == 1.0) stage_seconds[std::string(stage)] = now - stage_start[std::string(stage)];
    };
    conform::SicpCompensationResult result;
    std::map<std::string, double> best_stages;
    double best = 1e300;
    for (int repeat = 0; repeat < 3; ++repeat) {
      const double t = best_seconds(
          1, [&] { result = conform::compensate_trajectory(panel.contour, &panel.surface, scan, nominal, options); });
      if (t < best) best = t, best_stages = stage_seconds;
    }
    const conform::TrajectoryError e = conform::trajectory_error(result.trajectory, truth, nominal);
    std::printf("%-11s %9.3f %9.4f %9.4f %9.4f %9.4f %7.0fx ", conform::to_string(model), best, e.path_mean_mm,
                e.path_max_mm, e.mean_mm, e.max_mm, 26.0 / best);
    for (const auto& [stage, seconds] : best_stages) std::printf(" %s %.3f;", stage.c_str(), seconds);
    std::printf("\n");
  }
  // The whole job from the files the generator writes (binary PLY scan and surface, CSV contour and trajectory).
  const std::string dir = (std::filesystem::temp_directory_path() / "conform_sicp_bench").string();
  std::filesystem::create_directories(dir);
  conform::GeneratePanelOptions generate;
  generate.panel = panel_options;
  generate.out_path = dir + "/nose.ply";
  const conform::GeneratePanelResult files = conform::run_generate_panel(generate);
  conform::SicpJobOptions job;
  job.contour_path = files.files.contour;
  job.scan_path = files.files.scan;
  job.trajectory_path = files.files.trajectory;
  job.surface_path = files.files.nominal;
  job.out_trajectory_path = dir + "/out.csv";
  const double with_files = best_seconds(3, [&] { conform::run_sicp(job); });
  std::printf("run_sicp with reading and writing files: %.3f s\n", with_files);
  std::filesystem::remove_all(dir);
  return 0;
}
