#include "conform/registration/sicp.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/registration/downsample.h"
#include "conform/registration/sicp_pairs.h"
#include "sicp_edge.h"
#include "sicp_selection.h"

namespace conform {
namespace {

// A segment's fine ICP with at least this share of its points paired needs no coarse pass first.
constexpr double kWellPaired = 0.9;

IcpOptions icp_options(const SicpOptions& o, bool surface, double max_distance_mm) {
  IcpOptions icp;
  icp.method = surface ? IcpMethod::kPointToSurface : IcpMethod::kPointToPoint;
  icp.max_correspondence_distance_mm = max_distance_mm;
  icp.max_iterations = o.max_iterations;
  icp.kernel = RobustKernel::kHuber;
  icp.coarse_points = 0;
  // A micrometre is far below the scan's noise; tighter tolerances only add iterations over small segments.
  icp.translation_tolerance_mm = 1e-3;
  icp.rotation_tolerance_rad = 1e-5;
  icp.min_inlier_fraction = 0.0;
  return icp;
}

Cloud to_cloud(const std::vector<Eigen::Vector3d>& points) {
  Cloud cloud;
  for (const Eigen::Vector3d& p : points) {
    cloud.points.push_back(
        pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  }
  return cloud;
}

bool lexicographic(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The residuals of the pairs of T_nominal_scan * points with the nominal surface within max_distance, judged by
// sicp_residuals (also into the running sums of the overall RMS). The points hung below the scan's edge (sorted,
// lexicographic) are left out: the residuals judged are the scan's own.
SicpResiduals pair_residuals(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T_nominal_scan,
                             const IcpReference& nominal, double max_distance_mm,
                             const std::vector<Eigen::Vector3d>& hung, double* sum_sq, std::size_t* count) {
  std::vector<double> d;
  for (const Eigen::Vector3d& p : points) {
    if (std::binary_search(hung.begin(), hung.end(), p, lexicographic)) continue;
    const Eigen::Vector3d x = T_nominal_scan * p;
    const ReferencePoint r = closest_on_reference(nominal, x, max_distance_mm);
    if (r.found) d.push_back(r.normal.dot(x - r.point));
  }
  const SicpResiduals residuals = sicp_residuals(std::move(d));
  *sum_sq += residuals.sum_sq;
  *count += residuals.count;
  return residuals;
}

void set_residuals(const SicpResiduals& r, SicpSegmentFit& f) {
  f.rms_mm = r.rms_mm;
  f.off_surface_share = r.off_surface_share;
}

// The segment ICPs, in parallel (each is independent, so the result does not depend on the thread count).
void fit_segments_from(const detail::SicpSelection& selection, const IcpReference& reference,
                       const std::vector<Eigen::Isometry3d>& starts, const SicpOptions& o,
                       std::vector<SicpSegmentFit>& fits, bool surface = true) {
  const auto count = static_cast<std::ptrdiff_t>(fits.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const std::vector<Eigen::Vector3d>& points = selection.segment_points[static_cast<std::size_t>(k)];
    SicpSegmentFit& fit = fits[static_cast<std::size_t>(k)];
    fit.neighbourhood_points = selection.neighbourhood_counts[static_cast<std::size_t>(k)];
    fit.stability_points = points.size() - fit.neighbourhood_points;
    if (points.size() < 6) continue;  // too little scan: the joint refinement ties it to its neighbours
    const Eigen::Isometry3d& T_start = starts[static_cast<std::size_t>(k)];
    fit.icp = icp(points, reference, T_start, icp_options(o, surface, o.max_distance_mm));
    // Where the part bends away from the start by more than the fine pair distance, many points find no pair: a
    // first pass at the coarse distance brings the segment within reach (beyond the paper, whose segments start from
    // the rigid pose). Only then: on a gently curved edge the wide pass can slide a segment that needed nothing.
    if (o.coarse_segment_pass && (!icp_usable(fit.icp) || fit.icp.inlier_fraction < kWellPaired)) {
      const IcpResult first = icp(points, reference, T_start, icp_options(o, surface, o.coarse_max_distance_mm));
      if (icp_usable(first)) {
        const IcpResult second = icp(points, reference, first.T_ref_scan, icp_options(o, surface, o.max_distance_mm));
        if (icp_usable(second) && (!icp_usable(fit.icp) || second.inlier_fraction > fit.icp.inlier_fraction))
          fit.icp = second;
      }
    }
    fit.converged = fit.icp.converged;
  }
}

void fit_segments(const detail::SicpSelection& selection, const IcpReference& reference, bool surface,
                  const Eigen::Isometry3d& T_start, const SicpOptions& o, std::vector<SicpSegmentFit>& fits) {
  fit_segments_from(selection, reference, std::vector<Eigen::Isometry3d>(fits.size(), T_start), o, fits, surface);
}

// The contour's chord over segment k's core (nominal frame, unit; zero when degenerate).
Eigen::Vector3d edge_direction(const Polyline& contour, const ContourSegmentation& g, std::size_t k) {
  const auto point_at = [&](double s) {
    if (g.closed) s = std::fmod(std::fmod(s, g.length_mm) + g.length_mm, g.length_mm);
    const auto it = std::lower_bound(g.arc_length_mm.begin(), g.arc_length_mm.end(), s);
    return contour.points[std::min<std::size_t>(static_cast<std::size_t>(it - g.arc_length_mm.begin()),
                                                contour.points.size() - 1)];
  };
  const ContourSegment& c = g.segments[k];
  const Eigen::Vector3d chord = point_at(c.start_mm + c.length_mm) - point_at(c.start_mm);
  return chord.norm() > 1e-9 ? Eigen::Vector3d(chord.normalized()) : Eigen::Vector3d::Zero();
}

// The rigid ICP of the contour's neighbourhood: first with the coarse pair distance over a neighbourhood widened by
// it (the scan is only roughly in place), then with the fine distance over the neighbourhood at the pose found.
Eigen::Isometry3d coarse_fit(const Polyline& contour, const detail::ContourLocator& locator,
                             const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference, bool surface,
                             const SicpOptions& o, IcpResult& coarse) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const double distances[2] = {o.coarse_max_distance_mm, o.max_distance_mm};
  const double widths[2] = {o.neighbourhood_mm + o.coarse_max_distance_mm, o.neighbourhood_mm};
  for (int pass = 0; pass < 2; ++pass) {
    // Ten candidates per point kept leave enough after the neighbourhood test, at a tenth of the searches.
    const std::vector<Eigen::Vector3d> moving = stride_downsample(
        surface ? locator.near_contour(stride_downsample(scan, 10 * o.coarse_points), T, widths[pass]) : contour.points,
        o.coarse_points);
    if (moving.size() < 6) {
      throw Error("S-ICP: fewer than 6 scan points lie within " + std::to_string(widths[pass]) +
                  " mm of the contour: is the scan in place (same frame and units as the contour)?");
    }
    IcpOptions options = icp_options(o, surface, distances[pass]);
    if (surface && pass == 0) options.method = IcpMethod::kPointToPlane;
    coarse = icp(moving, reference, T, options);
    T = coarse.T_ref_scan;
  }
  return T;
}

// The segment ICPs (and, with a surface, the reselection at their own poses and the second round); fills
// result.segments and their starting transforms for the joint refinement (nominal <- scan with a surface); returns
// the selection the transforms were fitted to.
detail::SicpSelection register_segments(const Polyline& contour, const detail::ContourLocator& locator,
                                        const std::vector<Eigen::Vector3d>& thin, const IcpReference& reference,
                                        bool surface, const Eigen::Isometry3d& T, const SicpOptions& options,
                                        SicpResult& result, std::vector<Eigen::Isometry3d>& transforms) {
  // Each segment keeps at most points_per_segment + stability_points_per_segment; four times that many candidates in
  // all are plenty (a segment's share of the scan is about its share of the contour).
  const std::size_t candidates =
      4 * result.segmentation.segments.size() * (options.points_per_segment + options.stability_points_per_segment);
  const std::vector<Eigen::Vector3d> scan_candidates = stride_downsample(thin, candidates);
  detail::SicpSelection selection =
      surface ? locator.select_scan(scan_candidates, T, options) : locator.select_contour(contour, options);
  result.segments.resize(result.segmentation.segments.size());
  fit_segments(selection, reference, surface, T, options, result.segments);
  if (surface && options.reselect) {
    // The segments' own poses select their scan again (the rigid pose may have put the edge out of reach), and the
    // segment ICPs run once more from those poses (fine distance only).
    std::vector<Eigen::Isometry3d> first;
    for (const SicpSegmentFit& f : result.segments) first.push_back(icp_usable(f.icp) ? f.icp.T_ref_scan : T);
    selection = locator.reselect_scan(scan_candidates, T, first, options);
    std::vector<SicpSegmentFit> again(result.segments.size());
    SicpOptions fine = options;
    fine.coarse_segment_pass = false;
    fit_segments_from(selection, reference, first, fine, again);
    result.segments = std::move(again);
  }
  for (std::size_t k = 0; k < result.segments.size(); ++k) {
    SicpSegmentFit& f = result.segments[k];
    f.usable = f.neighbourhood_points + f.stability_points >= 6 && icp_usable(f.icp);
    transforms.push_back(f.usable ? f.icp.T_ref_scan : T);
    if (!f.usable) {
      result.warnings.push_back(
          "segment " + std::to_string(k) + ": " + std::to_string(f.neighbourhood_points) +
          " neighbourhood points, its ICP " +
          (f.neighbourhood_points + f.stability_points < 6 ? "did not run" : to_string(f.icp.termination)) +
          "; it starts from the rigid pose and the joint refinement ties it to its neighbours");
    }
  }
  return selection;
}

// Every segment's final transform (scan <- nominal) and the RMS of its pairs there; the overall RMS.
void final_residuals(const detail::SicpSelection& selection, const IcpReference& reference, bool surface,
                     const std::vector<Eigen::Isometry3d>& transforms, const std::vector<Eigen::Vector3d>& hung,
                     const SicpOptions& options, SicpResult& result) {
  double sum_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < transforms.size(); ++k) {
    SicpSegmentFit& f = result.segments[k];
    if (surface) {
      f.T_scan_nominal = transforms[k].inverse();
      set_residuals(pair_residuals(selection.segment_points[k], transforms[k], reference, options.max_distance_mm, hung,
                                   &sum_sq, &count),
                    f);
    } else {
      f.T_scan_nominal = transforms[k];
      f.rms_mm = f.icp.rms_mm;
      sum_sq += f.rms_mm * f.rms_mm * static_cast<double>(f.icp.inliers);
      count += f.icp.inliers;
    }
  }
  result.rms_mm = count > 0 ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
}

// The rigid model judged like S-ICP: every segment at the one rigid pose, with the scan it selects there and the RMS
// of its pairs, so that the checks (compensation/sicp_checks.h) see the rigid fit stretch by stretch.
void rigid_segments(const detail::ContourLocator& locator, const std::vector<Eigen::Vector3d>& thin,
                    const IcpReference& reference, const Eigen::Isometry3d& T, const std::vector<Eigen::Vector3d>& hung,
                    const SicpOptions& options, SicpResult& result) {
  const std::size_t candidates =
      4 * result.segmentation.segments.size() * (options.points_per_segment + options.stability_points_per_segment);
  const detail::SicpSelection selection = locator.select_scan(stride_downsample(thin, candidates), T, options);
  result.segments.resize(result.segmentation.segments.size());
  double sum_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < result.segments.size(); ++k) {
    SicpSegmentFit& f = result.segments[k];
    f.T_scan_nominal = T.inverse();
    f.neighbourhood_points = selection.neighbourhood_counts[k];
    f.stability_points = selection.segment_points[k].size() - f.neighbourhood_points;
    f.converged = result.coarse.converged;
    f.usable = icp_usable(result.coarse);
    set_residuals(
        pair_residuals(selection.segment_points[k], T, reference, options.max_distance_mm, hung, &sum_sq, &count), f);
  }
  result.segment_scan = selection.segment_points;
}

}  // namespace

SicpResiduals sicp_residuals(std::vector<double> d) {
  SicpResiduals r;
  if (d.empty()) return r;
  const auto middle = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double centre = middle(d);
  std::vector<double> spread;
  for (double x : d) spread.push_back(std::abs(x - centre));
  // At least 0.2 mm (4 x the 0.05 mm the checks take as the least noise, compensation/sicp_checks.h): a rigid
  // segment's own misfit on a smoothly deformed part (0.06-0.15 mm RMS) is not off the surface when the scan is quiet
  // (at 0.02 mm noise it was, for 5% of the points and more: good paths refused).
  const double cut = std::max(4.0 * 1.4826 * middle(spread), 0.2);
  std::size_t off = 0;
  for (double x : d) {
    if (std::abs(x - centre) > cut) {
      ++off;
      continue;
    }
    r.sum_sq += x * x;
    ++r.count;
  }
  r.rms_mm = r.count > 0 ? std::sqrt(r.sum_sq / static_cast<double>(r.count)) : 0.0;
  r.off_surface_share = static_cast<double>(off) / static_cast<double>(d.size());
  return r;
}

bool icp_usable(const IcpResult& r) { return r.converged || r.termination == IcpTermination::kMaxIterations; }

bool SicpOptions::IsValid(std::string* error) const {
  std::string why;
  const auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return false;
  };
  if (!segmentation.IsValid(&why)) return fail(why);
  if (joint_refinement && !joint.IsValid(&why)) return fail(why);
  if (!std::isfinite(scan_voxel_mm) || scan_voxel_mm < 0.0) return fail("scan voxel must be >= 0 mm");
  if (!std::isfinite(neighbourhood_mm) || neighbourhood_mm <= 0.0) return fail("neighbourhood must be > 0 mm");
  if (!std::isfinite(stability_mm) || stability_mm < neighbourhood_mm)
    return fail("stability distance must be >= the neighbourhood distance");
  if (!std::isfinite(coarse_max_distance_mm) || coarse_max_distance_mm <= 0.0)
    return fail("coarse maximum distance must be > 0 mm");
  if (!std::isfinite(max_distance_mm) || max_distance_mm <= 0.0) return fail("maximum distance must be > 0 mm");
  if (points_per_segment < 6) return fail("points per segment must be >= 6");
  if (coarse_points < 6) return fail("coarse points must be >= 6");
  if (max_iterations < 1 || max_iterations > 1000) return fail("ICP iterations must be in [1, 1000]");
  if (neighbourhood_mm > 1000.0 || stability_mm > 1000.0 || coarse_max_distance_mm > 1000.0 || max_distance_mm > 1000.0)
    return fail("neighbourhood, stability and pair distances must be <= 1000 mm");
  if (points_per_segment > 100000 || stability_points_per_segment > 100000 || coarse_points > 1000000)
    return fail("points per segment must be <= 1e5, coarse points <= 1e6");
  return true;
}

SicpResult sicp_register(const Polyline& contour, const IcpReference* nominal_surface,
                         const std::vector<Eigen::Vector3d>& scan, const SicpOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("S-ICP options: " + why);
  if (scan.empty()) throw Error("S-ICP: the scan has no points");
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan[i].allFinite()) throw Error("S-ICP: scan point " + std::to_string(i) + " is not finite");
  }
  SicpResult result;
  result.segmentation = segment_contour(contour, options.segmentation);
  std::vector<Eigen::Vector3d> thin =
      options.scan_voxel_mm > 0.0 ? voxel_downsample(scan, options.scan_voxel_mm) : scan;
  result.scan_points_used = thin.size();
  const bool surface = nominal_surface != nullptr;
  std::vector<Eigen::Vector3d> hung;
  if (surface && options.scan_edge) {
    detail::ScanEdge edge = detail::find_scan_edge(thin, contour, *nominal_surface,
                                                   options.neighbourhood_mm + options.coarse_max_distance_mm);
    result.scan_edge = std::move(edge.boundary);
    hung = std::move(edge.hung);
    thin.insert(thin.end(), hung.begin(), hung.end());
    std::sort(hung.begin(), hung.end(), lexicographic);
  }
  // Without a surface the contour moves onto the scan (the paper's direction); with one, the scan onto the surface.
  std::unique_ptr<IcpReference> scan_reference;
  if (!surface) scan_reference = std::make_unique<IcpReference>(to_cloud(thin));
  const IcpReference& reference = surface ? *nominal_surface : *scan_reference;
  const detail::ContourLocator locator(contour, result.segmentation);

  report(options.progress, "sicp: coarse", 0.0);
  // Nominal <- scan with a surface, scan <- nominal without.
  const Eigen::Isometry3d T = coarse_fit(contour, locator, thin, reference, surface, options, result.coarse);
  result.T_scan_nominal_rigid = surface ? T.inverse() : T;
  report(options.progress, "sicp: coarse", 1.0);
  // One rule for every ICP here (icp_usable): its iteration limit is the option max_iterations, and a fit that reaches
  // it is kept; whether its pose is good is judged by its residuals against the noise (compensation/sicp_checks.h).
  result.converged = icp_usable(result.coarse);
  result.termination =
      result.converged ? "converged" : std::string("coarse ICP: ") + to_string(result.coarse.termination);
  result.rms_mm = result.coarse.rms_mm;
  if (options.rigid_only) {
    if (surface) rigid_segments(locator, thin, reference, T, hung, options, result);
    return result;
  }

  report(options.progress, "sicp: segments", 0.0);
  std::vector<Eigen::Isometry3d> transforms;
  const detail::SicpSelection selection =
      register_segments(contour, locator, thin, reference, surface, T, options, result, transforms);
  report(options.progress, "sicp: segments", 1.0);

  if (surface && options.joint_refinement) {
    report(options.progress, "sicp: joint", 0.0);
    std::vector<SicpJointSegment> data(transforms.size());
    for (std::size_t k = 0; k < data.size(); ++k) {
      data[k].points = stride_downsample(selection.segment_points[k], options.joint.points_per_segment);
      data[k].along = edge_direction(contour, result.segmentation, k);
    }
    result.joint = refine_segments_jointly(data, locator.junctions(options.joint.points_per_overlap), reference,
                                           options.max_distance_mm, options.joint, transforms);
    if (!result.joint.usable && result.converged) {
      result.converged = false;
      result.termination = "joint refinement: " + result.joint.termination;
    }
    report(options.progress, "sicp: joint", 1.0);
  } else {
    result.joint.termination = surface ? "off" : "needs a nominal surface";
  }

  final_residuals(selection, reference, surface, transforms, hung, options, result);
  result.segment_scan = selection.segment_points;
  return result;
}

}  // namespace conform
