#include "conform/pipelines/generate/generate_tube_json.h"

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

// deg / 180 first, so that 90 deg is exactly pi / 2.

}  // namespace

GenerateTubeOptions generate_tube_options(const GenerateTubeRequest& request) {
  if (request.noise_type != "gaussian" && request.noise_type != "uniform") {
    throw Error("--noise-type " + request.noise_type + ": use gaussian or uniform");
  }
  if (request.noise_direction != "normal" && request.noise_direction != "isotropic") {
    throw Error("--noise-direction " + request.noise_direction + ": use normal or isotropic");
  }
  GenerateTubeOptions options;
  options.out_path = request.out_path;
  options.encoding = request.ascii ? Encoding::kAscii : Encoding::kBinary;
  options.double_precision = request.double_precision;
  TubeOptions& t = options.tube;
  t = request.tube;
  t.arc_rad = radians(request.arc_deg);
  t.arc_center_rad = radians(request.arc_center_deg);
  t.surface = request.inner ? TubeSurface::kInner : TubeSurface::kOuter;
  t.ovality_azimuth_rad = radians(request.ovality_azimuth_deg);
  t.seam_azimuth_rad = radians(request.seam_azimuth_deg);
  t.bow_azimuth_rad = radians(request.bow_azimuth_deg);
  t.noise_distribution = request.noise_type == "uniform" ? NoiseDistribution::kUniform : NoiseDistribution::kGaussian;
  t.noise_direction = request.noise_direction == "isotropic" ? NoiseDirection::kIsotropic : NoiseDirection::kNormal;
  t.seed = request.seed;
  for (const std::array<double, 4>& v : request.bumps) t.bumps.push_back({radians(v[0]), v[1], v[2], v[3]});
  for (const std::array<double, 3>& v : request.holes) t.holes.push_back({radians(v[0]), v[1], v[2]});
  const Eigen::Vector3d reference =
      request.azimuth_reference ? *request.azimuth_reference : default_azimuth_reference(request.axis_direction);
  t.T_world_tube = tube_frame(request.axis_point, request.axis_direction, reference);
  t.vertex_normals = request.normals;
  return options;
}

nlohmann::json generate_tube_json(const GenerateTubeResult& r) {
  nlohmann::json truth = r.truth;
  truth["scanner"]["outliers"].erase("indices");
  return {{"mesh", r.mesh_path},
          {"truth_file", r.truth_path},
          {"vertices", r.vertices},
          {"faces", r.faces},
          {"holes", r.holes},
          {"outliers", r.outliers},
          {"surface_area_mm2", r.surface_area_mm2},
          {"truth", truth}};
}

}  // namespace conform
