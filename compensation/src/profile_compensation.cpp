#include "conform/compensation/profile_compensation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform {
namespace {

std::string feature_name(const ProfileFeature& f) {
  return (f.where.empty() ? std::string() : f.where + ": ") + "feature '" + f.id + "' (" + to_string(f.type) + ")";
}

// Ty within the measured edge (of the model used), Tx on the web.
void check_feature_range(const ProfileFeature& feature, double length_mm, double width_mm,
                         const std::string& edge_source) {
  double lo = 0.0, hi = 0.0, tx_lo = 0.0, tx_hi = 0.0;
  feature.ty_range(&lo, &hi);
  feature.tx_range(&tx_lo, &tx_hi);
  char text[400];
  if (lo < 0.0 || hi > length_mm) {
    std::snprintf(text, sizeof(text),
                  " reaches Ty = %.3f mm, beyond the measured edge (%s: %.3f mm long, from Ty = 0 at its first "
                  "point)%s",
                  lo < 0.0 ? lo : hi, edge_source.c_str(), length_mm,
                  hi > 100.0 * length_mm ? "; is the edge in metres? Edge coordinates must be mm" : "");
    throw Error(feature_name(feature) + text);
  }
  if (tx_lo < 0.0) {
    std::snprintf(text, sizeof(text),
                  " reaches Tx = %.3f mm, beyond the measured edge (off the web: Tx runs from the edge, 0, "
                  "across the web)",
                  tx_lo);
    throw Error(feature_name(feature) + text);
  }
  if (width_mm > 0.0 && tx_hi > width_mm) {
    std::snprintf(text, sizeof(text), " reaches Tx = %.3f mm, beyond the web's width of %.3f mm", tx_hi, width_mm);
    throw Error(feature_name(feature) + text);
  }
}

// Features in metres against an edge in mm: every feature within a thousandth of the edge's length of the origin.
void check_units(const std::vector<ProfileFeature>& features, double length_mm, const std::string& edge_source) {
  if (features.empty() || length_mm < 2000.0) return;
  double reach = 0.0;
  for (const ProfileFeature& f : features) {
    double lo = 0.0, hi = 0.0, tx_lo = 0.0, tx_hi = 0.0;
    f.ty_range(&lo, &hi);
    f.tx_range(&tx_lo, &tx_hi);
    reach = std::max({reach, std::abs(lo), std::abs(hi), std::abs(tx_lo), std::abs(tx_hi)});
  }
  if (reach > length_mm / 1000.0) return;
  char text[400];
  std::snprintf(text, sizeof(text),
                "the features reach at most %.3f mm from the origin on an edge %.1f mm long (%s): are the features "
                "in metres? Tx and Ty must be mm",
                reach, length_mm, edge_source.c_str());
  throw Error(text);
}

// The map of the chosen model and the cubic-only map with the same web handling.
struct Maps {
  ProfileMap chosen;
  ProfileMap cubic;
};

Maps make_maps(const ProfileCompensationResult& r, double tolerance_mm) {
  if (r.local_web) {
    return {ProfileMap(r.edge.curve, r.second_edge->curve, tolerance_mm),
            ProfileMap(r.edge.cubic, r.second_edge->cubic, tolerance_mm)};
  }
  return {ProfileMap(r.edge.curve, r.web_normal, tolerance_mm), ProfileMap(r.edge.cubic, r.web_normal, tolerance_mm)};
}

constexpr double kDegree = 3.141592653589793 / 180.0;

// Z or the second edge: the web direction of the result (profile_map.h).
void choose_web(const std::vector<Eigen::Vector3d>& edge_points, const ProfileCompensationOptions& options,
                const std::vector<Eigen::Vector3d>* second_edge_points, const std::string& second_edge_source,
                ProfileCompensationResult* r) {
  if (second_edge_points != nullptr) {
    ProfileEdgeFitOptions second = options.edge;
    second.model = r->edge.model;  // the same kind of curve on both edges
    // The local map walks both edges side by side: a second edge listed the other way round is turned.
    std::vector<Eigen::Vector3d> turned;
    const std::vector<Eigen::Vector3d>& listed = *second_edge_points;
    const bool opposite = listed.size() >= 2 && edge_points.size() >= 2 &&
                          (listed.back() - listed.front()).dot(edge_points.back() - edge_points.front()) < 0.0;
    if (opposite) turned.assign(listed.rbegin(), listed.rend());
    r->second_edge = fit_profile_edge(opposite ? turned : listed, second, second_edge_source);
    r->local_web = true;
    r->web_source = "second edge";
    for (const std::string& w : r->second_edge->warnings) r->warnings.push_back(w);
    return;
  }
  if (options.web_normal) {
    r->web_normal = options.web_normal->normalized();
    r->web_source = "given";
  } else if (options.fit_web_plane) {
    const ProfileWebNormal plane = fit_profile_web_normal(edge_points);
    r->web_normal = plane.normal;
    r->web_flatness_ratio = plane.flatness_ratio;
    r->web_source = "fitted plane";
  }
  r->web_tilt_deg = std::acos(std::clamp(r->web_normal.z(), -1.0, 1.0)) / kDegree;
  if (options.fit_web_plane && r->web_tilt_deg > options.web_plane_warning_deg) {
    char text[300];
    std::snprintf(text, sizeof(text),
                  "the fitted web plane is tilted %.2f deg from machine +z, which moves a feature by %.2f mm per "
                  "100 mm of Tx: if the edge bends out of the web (sag) the plane follows the bend, not the web; "
                  "check it, or use machine +z (drop --web-plane)",
                  r->web_tilt_deg, 100.0 * std::sin(r->web_tilt_deg * kDegree));
    r->warnings.push_back(text);
  }
}

// With a second edge the web's width is measured: no feature may reach beyond it (1 mm for the fit's noise).
void check_measured_width(const std::vector<ProfileFeature>& features, double width_mm, const std::string& source) {
  for (const ProfileFeature& f : features) {
    double lo = 0.0, hi = 0.0;
    f.tx_range(&lo, &hi);
    if (hi <= width_mm + 1.0) continue;
    char text[300];
    std::snprintf(text, sizeof(text), " reaches Tx = %.3f mm, beyond the web's width measured by %s (at most %.3f mm)",
                  hi, source.c_str(), width_mm);
    throw Error(feature_name(f) + text);
  }
}

// The second edge must lie on the side V1 = Z x V points to (Eq. 5, Z = +z): on the other side, the edge was
// measured from the profile's far end (or the web faces down), and Ty would run from the wrong end.
void check_direction(const ProfileCompensationResult& r, const std::string& edge_source) {
  const ProfileEdgeCurve& edge = r.edge.curve;
  const double t = edge.approximate_parameter_at(0.5 * edge.length_mm());
  const Eigen::Vector3d c = edge.position(t);
  const Eigen::Vector3d v1 = Eigen::Vector3d::UnitZ().cross(edge.derivative(t, 1)).normalized();
  const ProfileEdgeCurve& second = r.second_edge->curve;
  const Eigen::Vector3d towards =
      second.position(second.approximate_parameter_at(0.5 * second.length_mm())) - c;
  if (v1.allFinite() && towards.dot(v1) < 0.0) {
    throw Error(edge_source +
                ": the second edge lies on the right of the measuring direction (seen from machine +z), where "
                "Tx < 0: the edge was measured from the profile's far end; give --direction reverse (or check "
                "that the web faces +z)");
  }
}

// Maps designed points with the chosen model, keeping the figures of every point mapped.
class FigureKeepingMap {
 public:
  FigureKeepingMap(const ProfileMap& map, double tolerance_mm, ProfileCompensationResult* r)
      : map_(map), tolerance_mm_(tolerance_mm), r_(r) {
    r_->web_width_min_mm = r_->local_web ? INFINITY : 0.0;
  }

  Eigen::Vector3d operator()(const Eigen::Vector2d& q) { return point(q).position; }

  ProfileMappedPoint point(const Eigen::Vector2d& q) {
    const ProfileMappedPoint p = map_.map(q.x(), q.y());
    r_->arc_length_residual_max_mm = std::max(r_->arc_length_residual_max_mm, std::abs(p.arc_length_residual_mm));
    converged_ = converged_ && std::abs(p.arc_length_residual_mm) <= tolerance_mm_;
    if (r_->local_web) {
      r_->web_width_min_mm = std::min(r_->web_width_min_mm, p.local_width_mm);
      r_->web_width_max_mm = std::max(r_->web_width_max_mm, p.local_width_mm);
    }
    return p;
  }
  bool converged() const { return converged_; }

 private:
  const ProfileMap& map_;
  double tolerance_mm_;
  ProfileCompensationResult* r_;
  bool converged_ = true;
};

// The cut direction at each point of a mapped outline: its central difference (one-sided at an open end, across the
// seam of a closed one), made perpendicular to the tool axis; the edge's direction where the outline has no length.
void cut_directions(const ProfileFeature& feature, const std::vector<ProfileMappedPoint>& frames,
                    ProfileFeatureResult* out) {
  const std::vector<Eigen::Vector3d>& p = out->mapped;
  const std::size_t n = p.size();
  const bool closed = feature.type != ProfileFeatureType::kPolyline && n > 2;
  out->directions.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t before = k > 0 ? k - 1 : (closed ? n - 2 : 0);
    std::size_t after = k + 1 < n ? k + 1 : (closed ? 1 : n - 1);
    Eigen::Vector3d d = n > 1 ? Eigen::Vector3d(p[after] - p[before]) : Eigen::Vector3d::Zero();
    d -= d.dot(out->normals[k]) * out->normals[k];
    out->directions[k] = d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : frames[k].tangent;
  }
}

// One feature: its sampled outline, mapped with its frames, its centre, and the worst distance to the cubic-only
// mapping.
ProfileFeatureResult map_feature(const ProfileFeature& feature, FigureKeepingMap* map, const ProfileMap* cubic,
                                 const ProfileSampleOptions& sampling) {
  ProfileFeatureResult out;
  out.id = feature.id;
  out.type = feature.type;
  out.designed = sample_profile_feature(
      feature, [map](const Eigen::Vector2d& q) { return (*map)(q); }, sampling);
  out.has_centre = feature.centre(&out.designed_centre);
  std::vector<Eigen::Vector2d> all = out.designed;
  if (out.has_centre) all.push_back(out.designed_centre);
  std::vector<ProfileMappedPoint> frames;
  frames.reserve(all.size());
  for (const Eigen::Vector2d& q : all) {
    frames.push_back(map->point(q));
    if (cubic != nullptr) {
      const Eigen::Vector3d c = cubic->map(q.x(), q.y()).position;
      out.cubic_deviation_max_mm = std::max(out.cubic_deviation_max_mm, (frames.back().position - c).norm());
    }
  }
  if (out.has_centre) {
    out.centre = frames.back().position;
    out.centre_normal = frames.back().normal;
    out.centre_direction = frames.back().tangent;
    frames.pop_back();
  }
  out.mapped.reserve(frames.size());
  out.normals.reserve(frames.size());
  for (const ProfileMappedPoint& f : frames) {
    out.mapped.push_back(f.position);
    out.normals.push_back(f.normal);
  }
  cut_directions(feature, frames, &out);
  return out;
}

}  // namespace

bool ProfileCompensationOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!edge.IsValid(&problem) || !sampling.IsValid(&problem)) {
  } else if (web_normal && (!web_normal->allFinite() || !(web_normal->norm() > 0.0))) {
    problem = "the web normal must be a finite, non-zero vector";
  } else if (!(web_plane_warning_deg >= 0.0) || !std::isfinite(web_plane_warning_deg)) {
    problem = "web_plane_warning_deg must be >= 0";
  } else if (!(web_width_mm >= 0.0) || !std::isfinite(web_width_mm)) {
    problem = "web_width_mm must be >= 0 (0: unknown)";
  } else if (fit_web_plane && web_normal) {
    problem = "give the web normal or ask for the fitted plane, not both";
  } else if (!(arc_length_tolerance_mm > 0.0)) {
    problem = "arc_length_tolerance_mm must be positive";
  } else if (!(gap_warning_mm >= 0.0) || !std::isfinite(gap_warning_mm)) {
    problem = "gap_warning_mm must be >= 0 (0: from the spacing)";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

namespace {

// Per feature: the stretches of edge without readings under it (consecutive edge points farther apart along the edge's
// axis than the limit; Ty ~ the projection on the axis from the first point), and, with one edge, the twist it cannot
// see. One summary line per kind in r->warnings.
void warn_per_feature(const ProfileCompensationOptions& options, ProfileCompensationResult* r) {
  const ProfileEdgePointsCheck& points = r->edge.points;
  const double limit =
      options.gap_warning_mm > 0.0 ? options.gap_warning_mm : std::max(20.0, 4.0 * points.median_spacing_mm);
  std::vector<std::pair<double, double>> gaps;
  for (std::size_t i = 1; i < points.along_mm.size(); ++i) {
    if (points.along_mm[i] - points.along_mm[i - 1] > limit)
      gaps.emplace_back(points.along_mm[i - 1], points.along_mm[i]);
  }
  const double per_deg = std::sin(kPi / 180.0);
  std::size_t twisted = 0;
  const ProfileFeatureResult* most = nullptr;
  for (ProfileFeatureResult& f : r->features) {
    double ty_min = 1e300, ty_max = -1e300, tx_max = 0.0;
    for (const Eigen::Vector2d& d : f.designed) {
      ty_min = std::min(ty_min, d.y()), ty_max = std::max(ty_max, d.y()), tx_max = std::max(tx_max, std::abs(d.x()));
    }
    if (f.has_centre) {
      ty_min = std::min(ty_min, f.designed_centre.y()), ty_max = std::max(ty_max, f.designed_centre.y());
      tx_max = std::max(tx_max, std::abs(f.designed_centre.x()));
    }
    for (const auto& [a, b] : gaps) {
      if (b < ty_min || a > ty_max) continue;
      f.gap_mm = std::max(f.gap_mm, b - a);
      const std::string text = "feature " + f.id + " (Ty " + format_fixed(ty_min, 1) + " to " +
                               format_fixed(ty_max, 1) + " mm) lies over a stretch of edge without readings (Ty " +
                               format_fixed(a, 1) + " to " + format_fixed(b, 1) + " mm, " + format_fixed(b - a, 1) +
                               " mm): its position there is interpolated; a kink or bend within it is not seen";
      f.warnings.push_back(text);
      r->warnings.push_back(text);
    }
    if (!r->local_web && tx_max > 0.0) {
      f.twist_mm_per_deg = tx_max * per_deg;
      f.warnings.push_back(
          "twist is not observed with one edge (give --second-edge): 1 deg of twist about the edge "
          "moves feature " +
          f.id + " by " + format_fixed(f.twist_mm_per_deg, 2) + " mm (Tx up to " + format_fixed(tx_max, 1) + " mm)");
      ++twisted;
      if (most == nullptr || f.twist_mm_per_deg > most->twist_mm_per_deg) most = &f;
    }
  }
  if (twisted > 0) {
    r->warnings.push_back("twist is not observed with one edge (give --second-edge): " + std::to_string(twisted) +
                          " features off the edge move by Tx sin(twist), up to " +
                          format_fixed(most->twist_mm_per_deg, 2) + " mm per degree (feature " + most->id + ")");
  }
}

}  // namespace

ProfileCompensationResult compensate_profile(const std::vector<Eigen::Vector3d>& edge_points,
                                             const std::vector<ProfileFeature>& features,
                                             const ProfileCompensationOptions& options,
                                             const std::vector<Eigen::Vector3d>* second_edge_points,
                                             const std::string& edge_source, const std::string& second_edge_source) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error("profile: invalid options: " + problem);
  ProfileCompensationResult r;
  std::vector<Eigen::Vector3d> reversed;
  if (options.reversed) reversed.assign(edge_points.rbegin(), edge_points.rend());
  const std::vector<Eigen::Vector3d>& edge = options.reversed ? reversed : edge_points;
  const std::string source = options.reversed ? edge_source + " (reversed)" : edge_source;
  r.edge = fit_profile_edge(edge, options.edge, source);
  r.warnings = r.edge.warnings;
  for (const ProfileFeature& feature : features) feature.validate();
  check_units(features, r.edge.curve.length_mm(), source);
  for (const ProfileFeature& feature : features) {
    check_feature_range(feature, r.edge.curve.length_mm(), options.web_width_mm, source);
  }
  choose_web(edge, options, second_edge_points, second_edge_source, &r);
  if (r.local_web) check_direction(r, source);
  const Maps maps = make_maps(r, options.arc_length_tolerance_mm);
  FigureKeepingMap map(maps.chosen, options.arc_length_tolerance_mm, &r);
  const ProfileMap* cubic = r.edge.model != ProfileEdgeModel::kCubic ? &maps.cubic : nullptr;
  for (const ProfileFeature& feature : features) {
    ProfileFeatureResult out = map_feature(feature, &map, cubic, options.sampling);
    r.mapped_points += out.mapped.size() + (out.has_centre ? 1 : 0);
    r.cubic_deviation_max_mm = std::max(r.cubic_deviation_max_mm, out.cubic_deviation_max_mm);
    r.features.push_back(std::move(out));
  }
  if (r.local_web) check_measured_width(features, r.web_width_max_mm, second_edge_source);
  warn_per_feature(options, &r);
  r.ok = map.converged();
  r.termination = r.ok ? "mapped every feature" : "an arc-length inversion missed its tolerance";
  return r;
}

}  // namespace conform
