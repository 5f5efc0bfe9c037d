// `conform align` as a user runs it (the whole process: start, reading the files, normals, coarse and fine
// registration, writing the transform) against its peers in the same run, on issue 13's two pairs:
//   fine: two independent 100k-point samplings of the ribbed plate (datasets/ribbed_plate.h, 0.02 mm noise),
//         2 deg / 3.7 mm apart, clouds: conform (default method) against PCL 1.13's IterativeClosestPoint and
//         Open3D's point-to-plane ICP and generalized ICP (reading the files and the normals included);
//   mesh: a partial scan (65 % of the plate, 80k points, 0.02 mm noise) in another frame (40 deg, 37 mm away)
//         against the plate's 306k-face height-field mesh (with a boss near a corner: datasets/ribbed_boss_plate.h), coarse + fine: conform `--init fpfh` against Open3D's
//         usual pipeline (voxel downsampling, normals, FPFH, RANSAC with mutual filter and the edge-length and distance
//         checkers, then point-to-plane ICP, or generalized ICP, on all points; reading the files included).
// Open3D runs in this process (no Python start-up, in its favour); conform as a child process (its start-up and file
// reading in the figure). Wall-clock, best of --repeats runs (default 3); CPU is user + system of the best run.
// Errors against the truth: the rotation angle of T_est T_truth^-1 and the distance the scan's centroid lands from
// where the truth puts it. Ratios > 1 mean the peer is slower.
// Usage: build/bench/align_peers_bench [--conform build/conform] [--baseline OTHER_CONFORM] [--repeats N] [--dir DIR]
//        [--seed N]
// (--baseline: another build of conform, e.g. before a change, timed in the same run; --seed: other samplings of
// the same pairs, default 1, issue 13's.) Under each conform row (and Open3D's pipeline) the time of each stage,
// from one more run: conform's progress lines on stderr, stamped as they come. On a shared machine run it
// with OMP_NUM_THREADS=1 and compare the cpu column: every program then runs on one thread, and other jobs' load
// inflates wall-clock time far more than CPU time.

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/io/TriangleMeshIO.h>
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/GeneralizedICP.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>
#include <open3d/utility/Logging.h>
#include <pcl/registration/icp.h>
#pragma GCC diagnostic pop

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/io.h"
#include "conform/core/mesh.h"
#include "conform/core/transform_io.h"
#include "conform/datasets/ribbed_boss_plate.h"
#include "conform/datasets/ribbed_plate.h"

extern char** environ;

namespace {

namespace o3r = open3d::pipelines::registration;
constexpr double kDeg = M_PI / 180.0;

struct Timing {
  double wall = std::numeric_limits<double>::infinity();
  double cpu = 0.0;
};

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double cpu_of(const rusage& u) {
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Starts `args` as a child process, stdout to /dev/null and stderr to `stderr_fd` (-1: /dev/null; the child does
// not inherit `close_fd`); exits the bench if it cannot.
pid_t spawn(const std::vector<std::string>& args, int stderr_fd = -1, int close_fd = -1) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  if (stderr_fd < 0) {
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  } else {
    posix_spawn_file_actions_adddup2(&actions, stderr_fd, 2);
  }
  if (close_fd >= 0) posix_spawn_file_actions_addclose(&actions, close_fd);
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed != 0) {
    std::fprintf(stderr, "cannot run %s\n", argv[0]);
    std::exit(2);
  }
  return pid;
}

// Runs `args` as a child process `repeats` times; exits the bench if it cannot start it.
Timing time_process(const std::vector<std::string>& args, int repeats) {
  Timing best;
  for (int r = 0; r < repeats; ++r) {
    const double start = now();
    const pid_t pid = spawn(args);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const double wall = now() - start;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "%s exited with %d\n", args[0].c_str(), WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
    if (wall < best.wall) best = {wall, cpu_of(usage)};
  }
  return best;
}

// One more run of `args` with its stderr read as it comes: the time from the start at which each progress line
// ("conform: <stage> ...") appeared, and the end. Printed as each stage's duration: where the process's time goes.
void print_stages(const std::vector<std::string>& args) {
  int fds[2];
  if (pipe(fds) != 0) return;
  const double start = now();
  const pid_t pid = spawn(args, fds[1], fds[0]);
  close(fds[1]);
  std::vector<std::pair<double, std::string>> stamps;
  std::string line;
  char c = 0;
  while (read(fds[0], &c, 1) == 1) {
    if (c != '\n') {
      line += c;
      continue;
    }
    const std::string prefix = "conform: ", suffix = " ...";
    if (line.rfind(prefix, 0) == 0 && line.size() > prefix.size() + suffix.size() &&
        line.compare(line.size() - suffix.size(), suffix.size(), suffix) == 0) {
      stamps.emplace_back(now() - start, line.substr(prefix.size(), line.size() - prefix.size() - suffix.size()));
    }
    line.clear();
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  const double end = now() - start;
  std::printf("    stages (s):");
  double last = 0.0;
  std::string name = "start";
  for (const auto& [t, stage] : stamps) {
    std::printf(" %s %.3f,", name.c_str(), t - last);
    last = t;
    name = stage;
  }
  std::printf(" %s %.3f; end %.3f\n", name.c_str(), end - last, end);
  std::fflush(stdout);
}

template <typename Fn>
Timing time_here(int repeats, Fn&& fn) {
  Timing best;
  for (int r = 0; r < repeats; ++r) {
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    const double start = now();
    fn();
    const double wall = now() - start;
    getrusage(RUSAGE_SELF, &after);
    if (wall < best.wall) best = {wall, cpu_of(after) - cpu_of(before)};
  }
  return best;
}

struct Case {
  std::string scan_file, reference_file;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();  // T_ref_scan
  Eigen::Vector3d scan_centroid = Eigen::Vector3d::Zero();  // scan frame
};

struct Row {
  std::string name;
  Timing time;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::vector<std::string> command;  // a child process's: its stages are printed under the row (print_stages)
  std::string stages;                // an in-process peer's stage times, its fastest run
};

void print_row(const Case& c, const Row& row, const Row& conform_row) {
  const Eigen::Isometry3d e = row.T * c.truth.inverse();
  const double rotation = std::atan2(0.5 * Eigen::Vector3d(e(2, 1) - e(1, 2), e(0, 2) - e(2, 0), e(1, 0) - e(0, 1)).norm(),
                                     0.5 * (e.linear().trace() - 1.0));
  const double translation = (row.T * c.scan_centroid - c.truth * c.scan_centroid).norm();
  std::printf("  %-50s %8.3f s %7.2fx %8.3f s %7.2fx  %9.5f deg %9.5f mm\n", row.name.c_str(), row.time.wall,
              row.time.wall / conform_row.time.wall, row.time.cpu, row.time.cpu / conform_row.time.cpu,
              rotation / kDeg, translation);
  if (!row.stages.empty()) std::printf("    stages (s): %s\n", row.stages.c_str());
  std::fflush(stdout);
  if (!row.command.empty()) print_stages(row.command);
}

Eigen::Isometry3d pose(double angle_deg, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle_deg * kDeg, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

conform::Cloud to_cloud(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T_out_in) {
  conform::Cloud cloud;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3f q = (T_out_in * p).cast<float>();
    cloud.points.push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  return cloud;
}

Eigen::Vector3d mean_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) m += p;
  return m / static_cast<double>(points.size());
}

// seed: the pair's samplings are seeds 2 seed - 1 (the reference) and 2 seed (the scan).
Case fine_case(const std::string& dir, std::uint64_t seed) {
  conform::RibbedPlateOptions o;
  o.seed = 2 * seed - 1;
  const std::vector<Eigen::Vector3d> reference = conform::ribbed_plate_samples(o);
  o.seed = 2 * seed;
  const std::vector<Eigen::Vector3d> scan = conform::ribbed_plate_samples(o);
  Case c;
  c.truth = pose(2.0, {1, 2, 3}, {3.0, -2.0, 1.0});  // 3.7 mm
  c.scan_centroid = c.truth.inverse() * mean_of(scan);
  c.reference_file = dir + "/fine_reference.ply";
  c.scan_file = dir + "/fine_scan.ply";
  conform::write_cloud(c.reference_file, to_cloud(reference, Eigen::Isometry3d::Identity()));
  conform::write_cloud(c.scan_file, to_cloud(scan, c.truth.inverse()));
  return c;
}

// seed: the scan's sampling is seed + 2 (the mesh is the same for every seed).
Case mesh_case(const std::string& dir, std::uint64_t seed, Case* near_case) {
  conform::RibbedPlateOptions o;
  o.seed = seed + 2;
  o.points = 123000;  // 65 % of them (x < 30 mm) are kept: ~80k
  std::vector<Eigen::Vector3d> scan;
  for (const Eigen::Vector3d& p : conform::ribbed_plate_samples(o)) {
    if (p.x() < 30.0) scan.emplace_back(p.x(), p.y(), p.z() + conform::ribbed_plate_boss_height(p.x(), p.y()));
  }
  Case c;
  c.truth = pose(40.0, {1, -2, 3}, {30.0, -20.0, 10.0});
  c.scan_centroid = c.truth.inverse() * mean_of(scan);
  c.reference_file = dir + "/mesh_reference.ply";
  c.scan_file = dir + "/mesh_scan.ply";
  const conform::Mesh mesh = conform::ribbed_boss_plate_mesh(o, 0.442);
  std::printf("mesh pair: scan %zu points, reference %zu vertices, %zu faces\n", scan.size(), mesh.vertices.size(),
              mesh.faces.size());
  conform::write_mesh(c.reference_file, mesh);
  conform::write_cloud(c.scan_file, to_cloud(scan, c.truth.inverse()));
  // The same scan 1 deg / 0.6 mm from the truth, for the fine registration alone (issue 13: "from 1 deg off").
  Case near = c;
  near.scan_file = dir + "/mesh_scan_near.ply";
  near.truth = pose(1.0, {3, 5, -8}, {0.5, -0.3, 0.2});
  near.scan_centroid = near.truth.inverse() * mean_of(scan);
  conform::write_cloud(near.scan_file, to_cloud(scan, near.truth.inverse()));
  *near_case = near;
  return c;
}

Row run_conform(const std::string& conform, const Case& c, const std::string& dir, const std::string& name,
                std::vector<std::string> extra, int repeats) {
  const std::string out = dir + "/T_" + std::to_string(std::hash<std::string>()(name)) + ".txt";
  std::vector<std::string> args = {conform, "align", "--scan", c.scan_file, "--reference", c.reference_file,
                                   "--out-transform", out};
  args.insert(args.end(), extra.begin(), extra.end());
  std::remove(out.c_str());
  Row row{name, time_process(args, repeats), Eigen::Isometry3d::Identity(), args, {}};
  struct stat st{};
  if (stat(out.c_str(), &st) == 0) row.T = conform::read_transform(out);
  return row;
}

Eigen::Isometry3d isometry(const Eigen::Matrix4d& m) {
  Eigen::Isometry3d T;
  T.matrix() = m;
  return T;
}

Row run_pcl_icp(const Case& c, int repeats) {
  const conform::Cloud scan = conform::read_cloud(c.scan_file), reference = conform::read_cloud(c.reference_file);
  pcl::PointCloud<pcl::PointXYZ>::Ptr source(new pcl::PointCloud<pcl::PointXYZ>(scan.points));
  pcl::PointCloud<pcl::PointXYZ>::Ptr target(new pcl::PointCloud<pcl::PointXYZ>(reference.points));
  Row row{"PCL IterativeClosestPoint (no file reading)", {}, Eigen::Isometry3d::Identity(), {}, {}};
  row.time = time_here(repeats, [&] {
    pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
    icp.setInputSource(source);
    icp.setInputTarget(target);
    icp.setMaxCorrespondenceDistance(10.0);
    icp.setMaximumIterations(50);
    icp.setTransformationEpsilon(1e-12);
    icp.setTransformationRotationEpsilon(1.0 - 1e-12);
    icp.setEuclideanFitnessEpsilon(1e-12);
    pcl::PointCloud<pcl::PointXYZ> aligned;
    icp.align(aligned);
    row.T = isometry(icp.getFinalTransformation().cast<double>());
  });
  return row;
}

std::shared_ptr<open3d::geometry::PointCloud> read_o3d_cloud(const std::string& path) {
  auto cloud = std::make_shared<open3d::geometry::PointCloud>();
  open3d::io::ReadPointCloud(path, *cloud);
  return cloud;
}

// The reference as Open3D takes it: a cloud's points with estimated normals, or a mesh's vertices with its normals.
std::shared_ptr<open3d::geometry::PointCloud> read_o3d_reference(const std::string& path, bool mesh, double radius) {
  if (!mesh) {
    auto cloud = read_o3d_cloud(path);
    cloud->EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(radius, 30));
    return cloud;
  }
  open3d::geometry::TriangleMesh m;
  open3d::io::ReadTriangleMesh(path, m);
  m.ComputeVertexNormals();
  auto cloud = std::make_shared<open3d::geometry::PointCloud>(m.vertices_);
  cloud->normals_ = m.vertex_normals_;
  return cloud;
}

const o3r::ICPConvergenceCriteria kCriteria(1e-6, 1e-6, 50);

Row run_o3d_fine(const Case& c, bool mesh, bool gicp, int repeats) {
  Row row{gicp ? "Open3D generalized ICP (reading, normals)" : "Open3D point-to-plane ICP (reading, normals)", {},
          Eigen::Isometry3d::Identity(), {}, {}};
  row.time = time_here(repeats, [&] {
    auto source = read_o3d_cloud(c.scan_file);
    auto target = read_o3d_reference(c.reference_file, mesh, 1.5);
    const o3r::RegistrationResult r =
        gicp ? o3r::RegistrationGeneralizedICP(*source, *target, 10.0, Eigen::Matrix4d::Identity(),
                                               o3r::TransformationEstimationForGeneralizedICP(), kCriteria)
             : o3r::RegistrationICP(*source, *target, 10.0, Eigen::Matrix4d::Identity(),
                                    o3r::TransformationEstimationPointToPlane(), kCriteria);
    row.T = isometry(r.transformation_);
  });
  return row;
}

// Open3D's global registration tutorial, with conform's automatic voxel (1/30 of the reference's diagonal).
Row run_o3d_pipeline(const Case& c, double voxel, bool gicp, int repeats) {
  Row row{gicp ? "Open3D FPFH + RANSAC + generalized ICP" : "Open3D FPFH + RANSAC + point-to-plane", {},
          Eigen::Isometry3d::Identity(), {}, {}};
  double best_wall = std::numeric_limits<double>::infinity();
  row.time = time_here(repeats, [&] {
    double t[6];
    t[0] = now();
    auto source = read_o3d_cloud(c.scan_file);
    auto target = read_o3d_reference(c.reference_file, true, 0.0);
    t[1] = now();
    auto source_down = source->VoxelDownSample(voxel), target_down = target->VoxelDownSample(voxel);
    for (auto& down : {source_down, target_down}) {
      down->EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(2.0 * voxel, 30));
    }
    t[2] = now();
    const auto source_fpfh = o3r::ComputeFPFHFeature(*source_down, open3d::geometry::KDTreeSearchParamHybrid(5.0 * voxel, 100));
    const auto target_fpfh = o3r::ComputeFPFHFeature(*target_down, open3d::geometry::KDTreeSearchParamHybrid(5.0 * voxel, 100));
    t[3] = now();
    const o3r::CorrespondenceCheckerBasedOnEdgeLength edges(0.9);
    const o3r::CorrespondenceCheckerBasedOnDistance distance(1.5 * voxel);
    std::srand(1);
    const o3r::RegistrationResult coarse = o3r::RegistrationRANSACBasedOnFeatureMatching(
        *source_down, *target_down, *source_fpfh, *target_fpfh, true, 1.5 * voxel,
        o3r::TransformationEstimationPointToPoint(false), 3, {edges, distance},
        o3r::RANSACConvergenceCriteria(100000, 0.999));
    t[4] = now();
    const o3r::RegistrationResult fine =
        gicp ? o3r::RegistrationGeneralizedICP(*source, *target, 0.4 * voxel, coarse.transformation_,
                                               o3r::TransformationEstimationForGeneralizedICP(), kCriteria)
             : o3r::RegistrationICP(*source, *target, 0.4 * voxel, coarse.transformation_,
                                    o3r::TransformationEstimationPointToPlane(), kCriteria);
    t[5] = now();
    row.T = isometry(fine.transformation_);
    if (t[5] - t[0] < best_wall) {
      best_wall = t[5] - t[0];
      char text[200];
      std::snprintf(text, sizeof text,
                    "reading and vertex normals %.3f, voxels and normals %.3f, FPFH %.3f, RANSAC %.3f, ICP %.3f",
                    t[1] - t[0], t[2] - t[1], t[3] - t[2], t[4] - t[3], t[5] - t[4]);
      row.stages = text;
    }
  });
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string conform = "build/conform", baseline, dir = "/tmp/conform_align_peers_bench";
  int repeats = 3;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--conform") conform = argv[i + 1];
    if (key == "--repeats") repeats = std::atoi(argv[i + 1]);
    if (key == "--dir") dir = argv[i + 1];
    if (key == "--baseline") baseline = argv[i + 1];
    if (key == "--seed") seed = std::max(1ULL, std::strtoull(argv[i + 1], nullptr, 10));
  }
  mkdir(dir.c_str(), 0755);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  std::printf("  %-50s %10s %8s %10s %8s  %13s %12s\n", "", "wall", "ratio", "cpu", "ratio", "rotation err",
              "centroid err");

  const Case fine = fine_case(dir, seed);
  std::printf("fine pair: 100k <-> 100k ribbed plate clouds, 2 deg / 3.7 mm apart (samplings %llu and %llu)\n",
              static_cast<unsigned long long>(2 * seed - 1), static_cast<unsigned long long>(2 * seed));
  const Row c1 = run_conform(conform, fine, dir, "conform align (whole process)", {}, repeats);
  print_row(fine, c1, c1);
  if (!baseline.empty()) print_row(fine, run_conform(baseline, fine, dir, "baseline conform align", {}, repeats), c1);
  print_row(fine, run_pcl_icp(fine, 1), c1);
  print_row(fine, run_o3d_fine(fine, false, false, repeats), c1);
  print_row(fine, run_o3d_fine(fine, false, true, repeats), c1);

  Case near;
  const Case mesh = mesh_case(dir, seed, &near);
  std::printf("mesh pair, fine only: the scan 1 deg / 0.6 mm off\n");
  const Row c2 = run_conform(conform, near, dir, "conform align (whole process)", {}, repeats);
  print_row(near, c2, c2);
  if (!baseline.empty()) print_row(near, run_conform(baseline, near, dir, "baseline conform align", {}, repeats), c2);
  print_row(near, run_conform(conform, near, dir, "conform align --method point-to-plane", {"--method", "point-to-plane"},
                              repeats),
            c2);
  print_row(near, run_o3d_fine(near, true, false, repeats), c2);
  print_row(near, run_o3d_fine(near, true, true, repeats), c2);

  std::printf("mesh pair, coarse + fine: the scan 40 deg / 37 mm off\n");
  const double voxel = std::hypot(200.0, 150.0, 8.0) / 30.0;
  const Row c3 = run_conform(conform, mesh, dir, "conform align --init fpfh (whole process)", {"--init", "fpfh"},
                             repeats);
  print_row(mesh, c3, c3);
  if (!baseline.empty()) {
    print_row(mesh, run_conform(baseline, mesh, dir, "baseline conform align --init fpfh", {"--init", "fpfh"}, repeats),
              c3);
  }
  print_row(mesh, run_conform(conform, mesh, dir, "conform align --init fpfh --method point-to-plane",
                              {"--init", "fpfh", "--method", "point-to-plane"}, repeats),
            c3);
  print_row(mesh, run_o3d_pipeline(mesh, voxel, false, repeats), c3);
  print_row(mesh, run_o3d_pipeline(mesh, voxel, true, repeats), c3);
  return 0;
}
