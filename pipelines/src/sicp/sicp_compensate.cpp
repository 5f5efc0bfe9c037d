#include <cmath>
#include <memory>

#include "conform/compensation/sicp_blend.h"
#include "conform/compensation/sicp_surface_misfit.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/pipelines/sicp/sicp.h"
#include "conform/registration/downsample.h"
#include "conform/registration/sicp_pairs.h"
#include "conform/registration/surface_noise.h"

namespace conform {
namespace {

// The scan's noise for the path checks: plane fits over 20 neighbours (a few mm on a 1 mm voxel scan) at 400 points.
const SurfaceNoiseOptions kScanNoise{20, 400};

// The projection model judged like the others: each segment's RMS is that of its scan points against the model's
// image of the nominal surface (the closest nominal point, mapped, along the mapped normal), not the rigid pose's.
void projection_residuals(const ProjectionModel& model, const IcpReference& nominal, double max_distance_mm,
                          SicpResult& registration) {
  const Eigen::Isometry3d T_nominal_scan = model.T_scan_nominal.inverse();
  for (std::size_t k = 0; k < registration.segments.size() && k < registration.segment_scan.size(); ++k) {
    std::vector<double> d;
    for (const Eigen::Vector3d& q : registration.segment_scan[k]) {
      const ReferencePoint c = closest_on_reference(nominal, T_nominal_scan * q, max_distance_mm);
      if (c.found) d.push_back((q - model.map_point(c.point)).dot(model.map_normal(c.point, c.normal)));
    }
    const SicpResiduals r = sicp_residuals(std::move(d));
    registration.segments[k].rms_mm = r.rms_mm;
    registration.segments[k].off_surface_share = r.off_surface_share;
  }
}

// The model's residual of a scan point at a trajectory row (sicp_surface_misfit): against the nominal surface mapped by
// the row's blended segment transforms (S-ICP: the residuals against both neighbours in an overlap, weighted as the
// path is), by the one rigid transform, or by the projection model's height field.
SicpModelResidual model_residual(const SicpCompensationResult& r, const Polyline& contour, const Trajectory& nominal,
                                 const IcpReference& reference, double max_distance_mm) {
  const SicpResult& g = r.registration;
  const auto against = [&reference, max_distance_mm](const Eigen::Isometry3d& T_scan_nominal,
                                                     const Eigen::Isometry3d& T_nominal_scan, const Eigen::Vector3d& q,
                                                     double& d, Eigen::Vector3d& n) {
    const Eigen::Vector3d x = T_nominal_scan * q;
    const ReferencePoint c = closest_on_reference(reference, x, max_distance_mm);
    if (!c.found) return false;
    d = c.normal.dot(x - c.point);
    n = T_scan_nominal.linear() * c.normal;
    return true;
  };
  if (r.model == SicpModel::kProjection) {
    const Eigen::Isometry3d T_nominal_scan = r.projection.T_scan_nominal.inverse();
    return [&r, &reference, max_distance_mm, T_nominal_scan](const Eigen::Vector3d& q, std::size_t, double& d,
                                                             Eigen::Vector3d& n) {
      const ReferencePoint c = closest_on_reference(reference, T_nominal_scan * q, max_distance_mm);
      if (!c.found) return false;
      n = r.projection.map_normal(c.point, c.normal);
      d = (q - r.projection.map_point(c.point)).dot(n);
      return true;
    };
  }
  if (r.model == SicpModel::kRigid || g.segments.empty()) {
    const Eigen::Isometry3d T = g.T_scan_nominal_rigid, T_inverse = T.inverse();
    return [against, T, T_inverse](const Eigen::Vector3d& q, std::size_t, double& d, Eigen::Vector3d& n) {
      return against(T, T_inverse, q, d, n);
    };
  }
  std::vector<Eigen::Isometry3d> T, T_inverse;
  for (const SicpSegmentFit& f : g.segments)
    T.push_back(f.T_scan_nominal), T_inverse.push_back(f.T_scan_nominal.inverse());
  const std::vector<double> s = locate_on_contour(contour, g.segmentation.arc_length_mm, nominal.points);
  return [against, T, T_inverse, s, &g](const Eigen::Vector3d& q, std::size_t row, double& d, Eigen::Vector3d& n) {
    const BlendAt b = blend_at(g.segmentation, s[row]);
    if (!against(T[b.segment], T_inverse[b.segment], q, d, n)) return false;
    if (b.next == b.segment || b.weight <= 0.0) return true;
    double d_next = 0.0;
    Eigen::Vector3d n_next;
    if (!against(T[b.next], T_inverse[b.next], q, d_next, n_next)) return true;
    d = (1.0 - b.weight) * d + b.weight * d_next;
    n = ((1.0 - b.weight) * n + b.weight * n_next).normalized();
    return true;
  };
}

}  // namespace

const char* to_string(SicpModel model) {
  switch (model) {
    case SicpModel::kRigid:
      return "rigid";
    case SicpModel::kProjection:
      return "projection";
    default:
      return "sicp";
  }
}

SicpCompensationResult compensate_trajectory(const Polyline& contour, const Mesh* surface,
                                             const std::vector<Eigen::Vector3d>& scan, const Trajectory& nominal,
                                             const SicpCompensationOptions& options) {
  check_trajectory(nominal, "trajectory");
  if (surface == nullptr) {
    throw Error(
        "S-ICP without a nominal surface (contour-only) is refused: the contour's points would pair with the scanned "
        "surface beside the edge, not with the edge, and the path comes out worse than one rigid transform; give "
        "--surface (the nominal surface mesh around the contour) or the nominal mesh as --contour");
  }
  SicpCompensationResult r;
  r.model = options.model;
  const double voxel = options.sicp.scan_voxel_mm;
  const std::vector<Eigen::Vector3d> thin = voxel > 0.0 ? voxel_downsample(scan, voxel) : scan;
  SicpOptions sicp = options.sicp;
  sicp.scan_voxel_mm = 0.0;  // thinned already
  sicp.rigid_only = options.model != SicpModel::kSicp;
  const auto reference = std::make_unique<IcpReference>(*surface);
  r.registration = sicp_register(contour, reference.get(), thin, sicp);
  r.registration.scan_points_used = thin.size();
  r.converged = r.registration.converged;
  r.termination = r.registration.termination;
  switch (options.model) {
    case SicpModel::kSicp: {
      std::vector<Eigen::Isometry3d> transforms;
      for (const SicpSegmentFit& f : r.registration.segments) transforms.push_back(f.T_scan_nominal);
      r.trajectory = map_by_segments(nominal, contour, r.registration.segmentation, transforms);
      break;
    }
    case SicpModel::kRigid:
      r.trajectory = map_rigidly(nominal, r.registration.T_scan_nominal_rigid);
      break;
    case SicpModel::kProjection: {
      r.projection =
          fit_projection_model(contour, *reference, thin, r.registration.T_scan_nominal_rigid, options.projection);
      projection_residuals(r.projection, *reference, options.sicp.max_distance_mm, r.registration);
      for (std::size_t i = 0; i < nominal.points.size(); ++i) {
        r.trajectory.points.push_back(r.projection.map_point(nominal.points[i]));
        r.trajectory.normals.push_back(r.projection.map_normal(nominal.points[i], nominal.normals[i]));
      }
      break;
    }
  }
  const KdTree tree(thin);
  if (options.normals.from_scan)
    r.normals_from_scan = reestimate_tool_normals(r.trajectory, thin, tree, options.normals);
  const std::vector<Eigen::Vector3d> predicted_normals = r.trajectory.normals;
  smooth_tool_normals(r.trajectory, options.normals.smooth_mm);
  const double noise = estimate_surface_noise(thin, tree, kScanNoise);
  // The surface misfit counts the scan's own points, not the thinned ones, with their own noise: a narrow dent's
  // evidence on the face is a handful of points (half a 10 mm dent at 0.5-0.65 points per mm^2), and the 1 mm voxels
  // merge about a third of them (docs/measurements/sicp.md, Narrow dents: the scan's own points).
  const std::unique_ptr<KdTree> full_tree = voxel > 0.0 ? std::make_unique<KdTree>(scan) : nullptr;
  const std::vector<Eigen::Vector3d>& misfit_scan = full_tree ? scan : thin;
  const KdTree& misfit_tree = full_tree ? *full_tree : tree;
  const double misfit_noise = full_tree ? estimate_surface_noise(scan, *full_tree, kScanNoise) : noise;
  const std::vector<SicpRowMisfit> misfit = sicp_surface_misfit(
      r.trajectory, predicted_normals, misfit_scan, misfit_tree, misfit_noise,
      model_residual(r, contour, nominal, *reference, options.sicp.max_distance_mm), options.misfit);
  r.check = check_sicp_path(
      contour, r.registration, nominal, r.trajectory, options.checks, noise,
      count_edge_points(tree, r.trajectory, options.checks.edge_radius_mm, 2 * options.checks.min_edge_points), misfit);
  r.trusted = r.check.trusted;
  return r;
}

}  // namespace conform
