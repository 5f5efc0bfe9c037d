#include "conform/compensation/profile_compensation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "conform/core/error.h"

namespace conform {
namespace {

void check_feature_range(const ProfileFeature& feature, double length_mm, const std::string& edge_source) {
  double lo = 0.0, hi = 0.0;
  feature.ty_range(&lo, &hi);
  if (lo >= 0.0 && hi <= length_mm) return;
  char text[300];
  std::snprintf(text, sizeof(text),
                "%s%sfeature '%s' (%s) reaches Ty = %.3f mm, beyond the measured edge (%s: %.3f mm "
                "long, from Ty = 0 at its first point)",
                feature.where.c_str(), feature.where.empty() ? "" : ": ", feature.id.c_str(), to_string(feature.type),
                lo < 0.0 ? lo : hi, edge_source.c_str(), length_mm);
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

// Z or the second edge: the web direction of the result (profile_map.h).
void choose_web(const std::vector<Eigen::Vector3d>& edge_points, const ProfileCompensationOptions& options,
                const std::vector<Eigen::Vector3d>* second_edge_points, const std::string& second_edge_source,
                ProfileCompensationResult* r) {
  if (second_edge_points != nullptr) {
    ProfileEdgeFitOptions second = options.edge;
    second.model = r->edge.model;  // the same kind of curve on both edges
    r->second_edge = fit_profile_edge(*second_edge_points, second, second_edge_source);
    r->local_web = true;
  } else if (options.web_normal) {
    r->web_normal = options.web_normal->normalized();
  } else {
    const ProfileWebNormal plane = fit_profile_web_normal(edge_points);
    r->web_normal = plane.normal;
    r->web_flatness_ratio = plane.flatness_ratio;
  }
}

// Maps designed points with the chosen model, keeping the figures of every point mapped.
class FigureKeepingMap {
 public:
  FigureKeepingMap(const ProfileMap& map, double tolerance_mm, ProfileCompensationResult* r)
      : map_(map), tolerance_mm_(tolerance_mm), r_(r) {
    r_->web_width_min_mm = r_->local_web ? INFINITY : 0.0;
  }

  Eigen::Vector3d operator()(const Eigen::Vector2d& q) {
    const ProfileMappedPoint p = map_.map(q.x(), q.y());
    r_->arc_length_residual_max_mm = std::max(r_->arc_length_residual_max_mm, std::abs(p.arc_length_residual_mm));
    converged_ = converged_ && std::abs(p.arc_length_residual_mm) <= tolerance_mm_;
    if (r_->local_web) {
      r_->web_width_min_mm = std::min(r_->web_width_min_mm, p.local_width_mm);
      r_->web_width_max_mm = std::max(r_->web_width_max_mm, p.local_width_mm);
    }
    return p.position;
  }
  bool converged() const { return converged_; }

 private:
  const ProfileMap& map_;
  double tolerance_mm_;
  ProfileCompensationResult* r_;
  bool converged_ = true;
};

// One feature: its sampled outline, mapped, its centre, and the worst distance to the cubic-only mapping.
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
  out.mapped.reserve(all.size());
  for (const Eigen::Vector2d& q : all) {
    out.mapped.push_back((*map)(q));
    if (cubic != nullptr) {
      const Eigen::Vector3d c = cubic->map(q.x(), q.y()).position;
      out.cubic_deviation_max_mm = std::max(out.cubic_deviation_max_mm, (out.mapped.back() - c).norm());
    }
  }
  if (out.has_centre) {
    out.centre = out.mapped.back();
    out.mapped.pop_back();
  }
  return out;
}

}  // namespace

bool ProfileCompensationOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!edge.IsValid(&problem) || !sampling.IsValid(&problem)) {
  } else if (web_normal && (!web_normal->allFinite() || !(web_normal->norm() > 0.0))) {
    problem = "the web normal must be a finite, non-zero vector";
  } else if (!(arc_length_tolerance_mm > 0.0)) {
    problem = "arc_length_tolerance_mm must be positive";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

ProfileCompensationResult compensate_profile(const std::vector<Eigen::Vector3d>& edge_points,
                                             const std::vector<ProfileFeature>& features,
                                             const ProfileCompensationOptions& options,
                                             const std::vector<Eigen::Vector3d>* second_edge_points,
                                             const std::string& edge_source, const std::string& second_edge_source) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error("profile: invalid options: " + problem);
  ProfileCompensationResult r;
  r.edge = fit_profile_edge(edge_points, options.edge, edge_source);
  for (const ProfileFeature& feature : features) {
    feature.validate();
    check_feature_range(feature, r.edge.curve.length_mm(), edge_source);
  }
  choose_web(edge_points, options, second_edge_points, second_edge_source, &r);
  const Maps maps = make_maps(r, options.arc_length_tolerance_mm);
  FigureKeepingMap map(maps.chosen, options.arc_length_tolerance_mm, &r);
  const ProfileMap* cubic = r.edge.model != ProfileEdgeModel::kCubic ? &maps.cubic : nullptr;
  for (const ProfileFeature& feature : features) {
    ProfileFeatureResult out = map_feature(feature, &map, cubic, options.sampling);
    r.mapped_points += out.mapped.size() + (out.has_centre ? 1 : 0);
    r.cubic_deviation_max_mm = std::max(r.cubic_deviation_max_mm, out.cubic_deviation_max_mm);
    r.features.push_back(std::move(out));
  }
  r.ok = map.converged();
  r.termination = r.ok ? "mapped every feature" : "an arc-length inversion missed its tolerance";
  return r;
}

}  // namespace conform
