#include "conform/datasets/tube.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {

namespace {

// Each effect draws from its own stream of the seed, so that e.g. adding outliers leaves the noise as it was.
enum Stream : std::uint64_t { kHoleStream = 1, kNoiseStream = 2, kOutlierStream = 3 };

constexpr int kHolePlacementAttempts = 1000;

double unrolled_distance(double radius, double theta_a, double z_a, double theta_b, double z_b) {
  return std::hypot(radius * wrap_angle(theta_a - theta_b), z_a - z_b);
}

// Random hole centres, uniform over the part of the surface where a whole disc fits, rejecting any that would
// overlap a hole already there.
std::vector<TubeHole> place_holes(const TubeOptions& o, const TubeGrid& grid) {
  std::vector<TubeHole> holes = o.holes;
  if (o.random_holes == 0) return holes;
  const double rho = o.random_hole_radius_mm;
  const double margin_rad = grid.closed ? 0.0 : rho / o.radius_mm;
  const double span = grid.columns * grid.column_step_rad;
  const double theta_lo = grid.theta_start_rad + margin_rad;
  const double theta_hi = grid.theta_start_rad + span - margin_rad;
  const double z_hi = 0.5 * o.length_mm - rho;
  std::ostringstream what_stream;
  what_stream << o.random_holes << " random holes of radius " << rho << " mm";
  const std::string what = what_stream.str();
  if (theta_hi <= theta_lo || z_hi <= -z_hi) throw Error("tube: " + what + " do not fit on the surface");

  Random random(o.seed, kHoleStream);
  for (int placed = 0; placed < o.random_holes; ++placed) {
    bool ok = false;
    for (int attempt = 0; attempt < kHolePlacementAttempts && !ok; ++attempt) {
      const TubeHole candidate{random.uniform(theta_lo, theta_hi), random.uniform(-z_hi, z_hi), rho};
      ok = std::none_of(holes.begin(), holes.end(), [&](const TubeHole& h) {
        return unrolled_distance(o.radius_mm, candidate.azimuth_rad, candidate.z_mm, h.azimuth_rad, h.z_mm) <
               candidate.radius_mm + h.radius_mm;
      });
      if (ok) holes.push_back(candidate);
    }
    if (!ok) throw Error("tube: cannot place " + what + " without overlap; ask for fewer or smaller holes");
  }
  return holes;
}

// Drops the faces whose centre (in theta, z) lies in a hole, then the vertices no face uses any more.
void cut_holes(const std::vector<TubeHole>& holes, double radius, std::vector<Eigen::Vector2d>& params,
               std::vector<Face>& faces) {
  if (holes.empty()) return;
  auto in_hole = [&](const Face& f) {
    const Eigen::Vector2d& a = params[static_cast<std::size_t>(f[0])];
    double dtheta = 0.0;  // relative to the first corner, so that a face across theta = +-pi averages correctly
    double z = 0.0;
    for (std::int32_t v : f) {
      dtheta += wrap_angle(params[static_cast<std::size_t>(v)].x() - a.x());
      z += params[static_cast<std::size_t>(v)].y();
    }
    const double theta = a.x() + dtheta / 3.0;
    return std::any_of(holes.begin(), holes.end(), [&](const TubeHole& h) {
      return unrolled_distance(radius, theta, z / 3.0, h.azimuth_rad, h.z_mm) < h.radius_mm;
    });
  };
  faces.erase(std::remove_if(faces.begin(), faces.end(), in_hole), faces.end());

  std::vector<std::int32_t> new_index(params.size(), -1);
  for (const Face& f : faces) {
    for (std::int32_t v : f) new_index[static_cast<std::size_t>(v)] = 0;
  }
  std::vector<Eigen::Vector2d> kept;
  for (std::size_t v = 0; v < params.size(); ++v) {
    if (new_index[v] < 0) continue;
    new_index[v] = static_cast<std::int32_t>(kept.size());
    kept.push_back(params[v]);
  }
  for (Face& f : faces) {
    for (std::int32_t& v : f) v = new_index[static_cast<std::size_t>(v)];
  }
  params = std::move(kept);
}

Eigen::Vector3d noise_offset(const TubeOptions& o, const Eigen::Vector3d& normal, Random& random) {
  const bool gaussian = o.noise_distribution == NoiseDistribution::kGaussian;
  if (o.noise_direction == NoiseDirection::kNormal) {
    return (gaussian ? o.noise_mm * random.normal() : random.uniform(-o.noise_mm, o.noise_mm)) * normal;
  }
  if (gaussian) {
    const double x = random.normal();
    const double y = random.normal();
    const double z = random.normal();
    return o.noise_mm * Eigen::Vector3d(x, y, z);
  }
  // Uniform in the ball of radius a, by rejection from the cube around it.
  Eigen::Vector3d v;
  do {
    const double x = random.uniform(-1.0, 1.0);
    const double y = random.uniform(-1.0, 1.0);
    const double z = random.uniform(-1.0, 1.0);
    v = Eigen::Vector3d(x, y, z);
  } while (v.squaredNorm() > 1.0);
  return o.noise_mm * v;
}

// A partial Fisher-Yates shuffle picks round(fraction * n) distinct vertices; each moves by d to 2d along its
// normal, to either side.
std::vector<std::int32_t> add_outliers(const TubeOptions& o, const std::vector<Eigen::Vector3d>& normals,
                                       std::vector<Eigen::Vector3d>& vertices) {
  const std::size_t n = vertices.size();
  const auto count = static_cast<std::size_t>(std::llround(o.outlier_fraction * static_cast<double>(n)));
  if (count == 0) return {};
  Random random(o.seed, kOutlierStream);
  std::vector<std::int32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::int32_t>(i);
  for (std::size_t i = 0; i < count; ++i) std::swap(order[i], order[i + random.below(n - i)]);
  order.resize(count);
  std::sort(order.begin(), order.end());
  for (std::int32_t v : order) {
    const double side = random.uniform() < 0.5 ? -1.0 : 1.0;
    const double distance = o.outlier_distance_mm * (1.0 + random.uniform());
    vertices[static_cast<std::size_t>(v)] += side * distance * normals[static_cast<std::size_t>(v)];
  }
  return order;
}

// Exact surface points and normals (world) of every vertex; progress in steps of about 1%.
void place_on_surface(const TubeOptions& o, TubeTruth& truth, std::vector<Eigen::Vector3d>& normals) {
  const std::size_t n = truth.vertex_parameters.size();
  truth.exact_vertices.resize(n);
  normals.resize(n);
  const std::size_t step = std::max<std::size_t>(1, n / 100);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = truth.vertex_parameters[i];
    const TubeSurfacePoint s = tube_surface(o, p.x(), p.y());
    truth.exact_vertices[i] = s.point;
    normals[i] = s.normal;
    if (i % step == 0) report(o.progress, "tube: vertices", static_cast<double>(i) / static_cast<double>(n));
  }
  report(o.progress, "tube: vertices", 1.0);
}

}  // namespace

TubeScan generate_tube(const TubeOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube options: " + why);

  TubeScan scan;
  TubeTruth& truth = scan.truth;
  truth.options = options;
  truth.options.progress = nullptr;
  truth.grid = tube_grid(options);
  truth.T_world_tube = options.T_world_tube;
  truth.axis_point = options.T_world_tube.translation();
  truth.axis_direction = options.T_world_tube.linear().col(2);
  truth.radius_mm = options.radius_mm;

  report(options.progress, "tube: faces", 0.0);
  truth.vertex_parameters = tube_grid_parameters(truth.grid);
  scan.mesh.faces = tube_grid_faces(truth.grid, options.surface);
  truth.holes = place_holes(options, truth.grid);
  cut_holes(truth.holes, options.radius_mm, truth.vertex_parameters, scan.mesh.faces);
  if (scan.mesh.faces.empty()) throw Error("tube: the holes remove the whole surface");
  report(options.progress, "tube: faces", 1.0);

  std::vector<Eigen::Vector3d> normals;
  place_on_surface(options, truth, normals);

  report(options.progress, "tube: scanner effects", 0.0);
  scan.mesh.vertices = truth.exact_vertices;
  if (options.noise_mm > 0.0) {
    Random random(options.seed, kNoiseStream);
    for (std::size_t i = 0; i < normals.size(); ++i) scan.mesh.vertices[i] += noise_offset(options, normals[i], random);
  }
  truth.outlier_indices = add_outliers(options, normals, scan.mesh.vertices);
  if (options.vertex_normals) scan.mesh.normals = vertex_normals_from_faces(scan.mesh);
  report(options.progress, "tube: scanner effects", 1.0);
  return scan;
}

}  // namespace conform
