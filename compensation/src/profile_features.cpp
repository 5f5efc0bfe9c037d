#include "conform/compensation/profile_features.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

// One piece of an outline: p(tau) on the flat profile for tau in [0, 1], and how many equal steps to start with.
struct Piece {
  std::function<Eigen::Vector2d(double)> at;
  int initial_steps = 1;
};

Piece line_piece(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return {[a, b](double tau) -> Eigen::Vector2d { return a + tau * (b - a); }, 1};
}

// The arc of radius r around c from angle `start` through `sweep` (rad); angle 0 points along +Tx.
Piece arc_piece(const Eigen::Vector2d& c, double r, double start, double sweep, double tolerance_mm) {
  // The chord of an arc of angle a deviates r (1 - cos(a / 2)) from it.
  const double step = r > tolerance_mm ? 2.0 * std::acos(1.0 - tolerance_mm / r) : kPi / 2.0;
  const int steps = std::max(4, static_cast<int>(std::ceil(std::abs(sweep) / std::min(step, kPi / 2.0))));
  return {[c, r, start, sweep](double tau) -> Eigen::Vector2d {
            const double angle = start + tau * sweep;
            return c + r * Eigen::Vector2d(std::cos(angle), std::sin(angle));
          },
          steps};
}

std::vector<Piece> pieces_of(const ProfileFeature& f, double tolerance_mm) {
  std::vector<Piece> pieces;
  const std::vector<Eigen::Vector2d>& v = f.vertices;
  switch (f.type) {
    case ProfileFeatureType::kPoint:
      break;
    case ProfileFeatureType::kCircle:
      pieces.push_back(arc_piece(v[0], f.radius_mm, 0.0, 2.0 * kPi, tolerance_mm));
      break;
    case ProfileFeatureType::kSlot: {
      const Eigen::Vector2d d = (v[1] - v[0]).normalized();
      const Eigen::Vector2d n(-d.y(), d.x());
      const double r = f.radius_mm;
      const double angle_n = std::atan2(n.y(), n.x());
      pieces.push_back(line_piece(v[0] + r * n, v[1] + r * n));
      pieces.push_back(arc_piece(v[1], r, angle_n, -kPi, tolerance_mm));  // +n through +d to -n
      pieces.push_back(line_piece(v[1] - r * n, v[0] - r * n));
      pieces.push_back(arc_piece(v[0], r, angle_n + kPi, -kPi, tolerance_mm));  // -n through -d to +n
      break;
    }
    case ProfileFeatureType::kPolyline:
    case ProfileFeatureType::kPolygon:
      for (std::size_t k = 0; k + 1 < v.size(); ++k) pieces.push_back(line_piece(v[k], v[k + 1]));
      if (f.type == ProfileFeatureType::kPolygon) pieces.push_back(line_piece(v.back(), v.front()));
      break;
  }
  return pieces;
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double f = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + f * ab - p).norm();
}

// Appends the designed points of (tau_a, tau_b] of `piece`, bisecting while the mapped middle is off the chord.
void refine(const Piece& piece, const ProfilePointMap& map, double tau_a, double tau_b, const Eigen::Vector3d& pa,
            const Eigen::Vector3d& pb, int depth, const ProfileSampleOptions& options,
            std::vector<Eigen::Vector2d>* out) {
  const double tau_m = 0.5 * (tau_a + tau_b);
  const Eigen::Vector2d m = piece.at(tau_m);
  const Eigen::Vector3d pm = map(m);
  if (depth < options.max_depth && distance_to_segment(pm, pa, pb) > options.chord_tolerance_mm) {
    refine(piece, map, tau_a, tau_m, pa, pm, depth + 1, options, out);
    refine(piece, map, tau_m, tau_b, pm, pb, depth + 1, options, out);
    return;
  }
  out->push_back(piece.at(tau_b));
}

}  // namespace

const char* to_string(ProfileFeatureType type) {
  switch (type) {
    case ProfileFeatureType::kPoint:
      return "point";
    case ProfileFeatureType::kCircle:
      return "circle";
    case ProfileFeatureType::kSlot:
      return "slot";
    case ProfileFeatureType::kPolyline:
      return "polyline";
    case ProfileFeatureType::kPolygon:
      return "polygon";
  }
  return "unknown";
}

bool parse_profile_feature_type(const std::string& text, ProfileFeatureType* type) {
  for (ProfileFeatureType t : {ProfileFeatureType::kPoint, ProfileFeatureType::kCircle, ProfileFeatureType::kSlot,
                               ProfileFeatureType::kPolyline, ProfileFeatureType::kPolygon}) {
    if (text == to_string(t)) {
      *type = t;
      return true;
    }
  }
  return false;
}

void ProfileFeature::validate() const {
  const std::string name =
      (where.empty() ? std::string() : where + ": ") + "feature '" + id + "' (" + to_string(type) + ")";
  std::size_t need_min = 1, need_max = 1;
  if (type == ProfileFeatureType::kSlot) need_min = need_max = 2;
  if (type == ProfileFeatureType::kPolyline) need_min = 2, need_max = SIZE_MAX;
  if (type == ProfileFeatureType::kPolygon) need_min = 3, need_max = SIZE_MAX;
  if (vertices.size() < need_min || vertices.size() > need_max) {
    throw Error(name + " has " + std::to_string(vertices.size()) + " rows; it needs " + std::to_string(need_min) +
                (need_max == need_min   ? ""
                 : need_max == SIZE_MAX ? " or more"
                                        : "") +
                " (rows with the same id)");
  }
  for (const Eigen::Vector2d& v : vertices) {
    if (!v.allFinite()) throw Error(name + " has a coordinate that is not finite");
    if (v.cwiseAbs().maxCoeff() > kProfileFeatureLimitMm) {
      char text[200];
      std::snprintf(text, sizeof(text), " has the coordinate (%.6g, %.6g) mm, beyond %.0f mm: not a profile's", v.x(),
                    v.y(), kProfileFeatureLimitMm);
      throw Error(name + text);
    }
  }
  const bool round = type == ProfileFeatureType::kCircle || type == ProfileFeatureType::kSlot;
  if (round && !(radius_mm > 0.0 && radius_mm <= kProfileFeatureLimitMm)) {
    char text[200];
    std::snprintf(text, sizeof(text), " needs a positive radius_mm up to %.0f mm, not %.6g", kProfileFeatureLimitMm,
                  radius_mm);
    throw Error(name + text);
  }
  if (type == ProfileFeatureType::kSlot && !((vertices[1] - vertices[0]).norm() > 0.0)) {
    throw Error(name + ": the two ends of the slot coincide (use a circle)");
  }
}

bool ProfileFeature::centre(Eigen::Vector2d* c) const {
  if (type == ProfileFeatureType::kCircle) {
    *c = vertices[0];
    return true;
  }
  if (type == ProfileFeatureType::kSlot) {
    *c = 0.5 * (vertices[0] + vertices[1]);
    return true;
  }
  return false;
}

void ProfileFeature::ty_range(double* lo, double* hi) const {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (const Eigen::Vector2d& v : vertices) {
    *lo = std::min(*lo, v.y());
    *hi = std::max(*hi, v.y());
  }
  if (type == ProfileFeatureType::kCircle || type == ProfileFeatureType::kSlot) {
    *lo -= radius_mm;
    *hi += radius_mm;
  }
}

void ProfileFeature::tx_range(double* lo, double* hi) const {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (const Eigen::Vector2d& v : vertices) {
    *lo = std::min(*lo, v.x());
    *hi = std::max(*hi, v.x());
  }
  if (type == ProfileFeatureType::kCircle || type == ProfileFeatureType::kSlot) {
    *lo -= radius_mm;
    *hi += radius_mm;
  }
}

bool ProfileSampleOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!(chord_tolerance_mm > 0.0) || !std::isfinite(chord_tolerance_mm)) {
    problem = "chord_tolerance_mm must be positive";
  } else if (max_depth < 0 || max_depth > 30) {
    problem = "max_depth must be in [0, 30]";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

std::vector<Eigen::Vector2d> sample_profile_feature(const ProfileFeature& feature, const ProfilePointMap& map,
                                                    const ProfileSampleOptions& options) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error("profile features: invalid sampling options: " + problem);
  feature.validate();
  if (feature.type == ProfileFeatureType::kPoint) return {feature.vertices[0]};
  const std::vector<Piece> pieces = pieces_of(feature, options.chord_tolerance_mm);
  std::vector<Eigen::Vector2d> out = {pieces.front().at(0.0)};
  for (const Piece& piece : pieces) {
    Eigen::Vector2d a = piece.at(0.0);
    Eigen::Vector3d pa = map(a);
    for (int k = 1; k <= piece.initial_steps; ++k) {
      const double tau_a = static_cast<double>(k - 1) / piece.initial_steps;
      const double tau_b = static_cast<double>(k) / piece.initial_steps;
      const Eigen::Vector3d pb = map(piece.at(tau_b));
      refine(piece, map, tau_a, tau_b, pa, pb, 0, options, &out);
      pa = pb;
    }
  }
  // A closed outline ends exactly on its first point (the last arc's tau = 1 lands there up to rounding).
  const bool closed = feature.type != ProfileFeatureType::kPolyline;
  if (closed) out.back() = out.front();
  return out;
}

}  // namespace conform
