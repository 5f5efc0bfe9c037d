#include "conform/toolpath/weld/parallel_paths.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "conform/core/error.h"

namespace conform {
namespace {

// Catmull-Rom through the polyline, t in [0, n - 1]: value, first and second derivative in (u, v).
struct ParameterCurve {
  const std::vector<Eigen::Vector2d>& p;
  double end() const { return static_cast<double>(p.size() - 1); }
  void eval(double t, Eigen::Vector2d* x, Eigen::Vector2d* d1, Eigen::Vector2d* d2) const {
    const std::size_t n = p.size();
    const std::size_t k = std::min(static_cast<std::size_t>(std::max(t, 0.0)), n - 2);
    const double s = t - static_cast<double>(k);
    const Eigen::Vector2d m0 = k == 0 ? Eigen::Vector2d(p[1] - p[0]) : Eigen::Vector2d(0.5 * (p[k + 1] - p[k - 1]));
    const Eigen::Vector2d m1 =
        k + 2 >= n ? Eigen::Vector2d(p[k + 1] - p[k]) : Eigen::Vector2d(0.5 * (p[k + 2] - p[k]));
    const double s2 = s * s, s3 = s2 * s;
    *x = (2 * s3 - 3 * s2 + 1) * p[k] + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p[k + 1] + (s3 - s2) * m1;
    *d1 = (6 * s2 - 6 * s) * p[k] + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p[k + 1] + (3 * s2 - 2 * s) * m1;
    *d2 = (12 * s - 6) * p[k] + (6 * s - 4) * m0 + (-12 * s + 6) * p[k + 1] + (6 * s - 2) * m1;
  }
};

// The space curve c(t) = r(u(t), v(t)) and its first two derivatives by the chain rule.
void space_curve(const ParametricSurface& surface, const ParameterCurve& curve, double t, Eigen::Vector2d* uv,
                 Eigen::Vector3d* c1, Eigen::Vector3d* c2) {
  Eigen::Vector2d d1, d2;
  curve.eval(t, uv, &d1, &d2);
  const double u = uv->x(), v = uv->y();
  const Eigen::Vector3d ru = surface.derivative(u, v, 1, 0), rv = surface.derivative(u, v, 0, 1);
  *c1 = ru * d1.x() + rv * d1.y();
  *c2 = surface.derivative(u, v, 2, 0) * d1.x() * d1.x() + 2.0 * surface.derivative(u, v, 1, 1) * d1.x() * d1.y() +
        surface.derivative(u, v, 0, 2) * d1.y() * d1.y() + ru * d2.x() + rv * d2.y();
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Crossing of segments ab and cd (parameters s on ab and t on cd in [0, 1]); false if parallel or apart.
bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d, Eigen::Vector2d* x) {
  const Eigen::Vector2d r = b - a, q = d - c;
  const double den = r.x() * q.y() - r.y() * q.x();
  if (std::abs(den) < 1e-300) return false;
  const Eigen::Vector2d w = c - a;
  const double s = (w.x() * q.y() - w.y() * q.x()) / den, t = (w.x() * r.y() - w.y() * r.x()) / den;
  if (s < 0.0 || s > 1.0 || t < 0.0 || t > 1.0) return false;
  if (x) *x = a + s * r;
  return true;
}

}  // namespace

bool ParallelPathOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(spacing_mm > 0.0) || !std::isfinite(spacing_mm)) return fail("path spacing must be > 0 mm");
  if (!(torch_distance_mm >= 0.0) || !std::isfinite(torch_distance_mm)) return fail("torch distance must be >= 0 mm");
  if (!(chord_error_mm > 0.0) || !std::isfinite(chord_error_mm)) return fail("chord error must be > 0 mm");
  if (!(max_step_mm > chord_error_mm) || !std::isfinite(max_step_mm)) return fail("max step must exceed the chord error");
  if (!(newton_ratio >= 0.0)) return fail("newton_ratio must be >= 0");
  if (normal_sign != 1 && normal_sign != -1) return fail("normal_sign must be +1 or -1");
  if (side != 1 && side != -1) return fail("side must be +1 or -1");
  if (max_paths < 1) return fail("max_paths must be >= 1");
  return true;
}

double SurfacePath::length_mm() const {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

double lateral_spacing(double spacing_mm, double torch_distance_mm, double normal_curvature) {
  const double k = normal_curvature;
  if (std::abs(k) * spacing_mm < 1e-9 || torch_distance_mm == 0.0) return spacing_mm;  // flat: g = dc
  const double R = 1.0 / std::abs(k);
  return k < 0.0 ? R / (R + torch_distance_mm) * spacing_mm : (R + torch_distance_mm) / R * spacing_mm;
}

double chord_for_error(double chord_error_mm, double radius_mm) {
  if (!(radius_mm > chord_error_mm)) return chord_error_mm;
  if (!std::isfinite(radius_mm)) return std::numeric_limits<double>::infinity();
  return 2.0 * std::sqrt(chord_error_mm * (radius_mm - chord_error_mm));
}

SurfacePath step_along(const ParametricSurface& surface, const std::vector<Eigen::Vector2d>& polyline,
                       const ParallelPathOptions& options, double* chord_error_max) {
  const ParameterCurve curve{polyline};
  SurfacePath path;
  const double end = curve.end();
  double t = 0.0;
  Eigen::Vector2d uv;
  Eigen::Vector3d c1, c2;
  space_curve(surface, curve, t, &uv, &c1, &c2);
  path.uv.push_back(uv);
  path.points.push_back(surface.position(uv.x(), uv.y()));
  while (t < end) {
    space_curve(surface, curve, t, &uv, &c1, &c2);
    const double speed = c1.norm();
    if (!(speed > 0.0)) break;
    // Eq. (2): the path's curvature; never less than the surface's normal curvature along it.
    const FundamentalForms forms = fundamental_forms(surface, uv.x(), uv.y());
    Eigen::Vector2d d1, d2, x;
    curve.eval(t, &x, &d1, &d2);
    const double kappa = std::max(c1.cross(c2).norm() / (speed * speed * speed),
                                  std::abs(forms.normal_curvature(d1.x(), d1.y())));
    const double chord = std::min(chord_for_error(options.chord_error_mm, kappa > 0 ? 1.0 / kappa : INFINITY),
                                  options.max_step_mm);
    double dt = chord / speed;  // Eq. (3)
    for (int halving = 0;; ++halving) {
      // A step that would leave a sliver (< 30%) before the end goes to the end: no tiny last segment, whose
      // direction would be noise for the next offset.
      const double t1 = t + 1.3 * dt >= end ? end : t + dt;
      const Eigen::Vector3d a = path.points.back();
      curve.eval(t1, &x, &d1, &d2);
      const Eigen::Vector3d b = surface.position(x.x(), x.y());
      double error = 0.0;
      for (int k = 1; k < 16; ++k) {
        curve.eval(t + (t1 - t) * k / 16.0, &x, &d1, &d2);
        error = std::max(error, distance_to_segment(surface.position(x.x(), x.y()), a, b));
      }
      if (error <= options.chord_error_mm || halving >= 30) {
        *chord_error_max = std::max(*chord_error_max, error);
        curve.eval(t1, &x, &d1, &d2);
        path.uv.push_back(x);
        path.points.push_back(b);
        t = t1;
        break;
      }
      dt *= 0.5;
    }
  }
  return path;
}

bool offset_point(const ParametricSurface& surface, const Eigen::Vector2d& uv, const Eigen::Vector2d& direction,
                  const ParallelPathOptions& options, Eigen::Vector2d* out, double* g, bool* exact) {
  *g = 0.0;
  return offset_point_by(surface, uv, direction, options, out, g, exact);
}

bool offset_point_by(const ParametricSurface& surface, const Eigen::Vector2d& uv, const Eigen::Vector2d& direction,
                     const ParallelPathOptions& options, Eigen::Vector2d* out, double* g, bool* exact) {
  const FundamentalForms f = fundamental_forms(surface, uv.x(), uv.y());
  const double up = direction.x(), vp = direction.y();
  const double speed = std::sqrt(f.first(up, vp)), H = std::sqrt(std::max(f.E * f.G - f.F * f.F, 0.0));
  if (!(speed > 0.0) || !(H > 0.0)) return false;
  // Eq. (8-9): the unit parameter direction perpendicular to the path in the surface metric.
  const Eigen::Vector2d across = options.side * Eigen::Vector2d(-(f.F * up + f.G * vp), f.E * up + f.F * vp) / (H * speed);
  const double k = options.normal_sign * f.normal_curvature(across.x(), across.y());
  if (!(*g > 0.0)) *g = lateral_spacing(options.spacing_mm, options.torch_distance_mm, k);
  Eigen::Vector2d x = uv + *g * across;
  *exact = std::abs(k) * *g > options.newton_ratio;
  if (*exact) {
    // Eq. (4/7) exactly: (r(x) - r0) . T = 0 and |r(x) - r0| = chord of the arc g on the normal section (radius R*).
    const double R = 1.0 / std::abs(k);
    const double chord = 2.0 * R * std::sin(std::min(*g / (2.0 * R), 1.5));
    const Eigen::Vector3d r0 = surface.position(uv.x(), uv.y());
    const Eigen::Vector3d T = (surface.derivative(uv.x(), uv.y(), 1, 0) * up + surface.derivative(uv.x(), uv.y(), 0, 1) * vp) / speed;
    for (int it = 0; it < 20; ++it) {
      const Eigen::Vector3d d = surface.position(x.x(), x.y()) - r0;
      const Eigen::Vector3d ru = surface.derivative(x.x(), x.y(), 1, 0), rv = surface.derivative(x.x(), x.y(), 0, 1);
      const Eigen::Vector2d F(d.dot(T), d.squaredNorm() - chord * chord);
      Eigen::Matrix2d J;
      J << ru.dot(T), rv.dot(T), 2.0 * d.dot(ru), 2.0 * d.dot(rv);
      const Eigen::Vector2d step = J.fullPivLu().solve(-F);
      if (!step.allFinite()) return false;
      x += step;
      if (step.norm() < 1e-13) break;
    }
  }
  *out = x;
  return surface.domain().contains(x.x(), x.y(), 1e-9);
}

std::vector<Eigen::Vector2d> remove_loops(const std::vector<Eigen::Vector2d>& polyline, std::size_t* loops,
                                          std::size_t* points) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& q : polyline) {
    if (out.size() >= 3) {
      Eigen::Vector2d x;
      for (std::size_t j = out.size() - 2; j-- > 0;) {
        if (segments_cross(out[j], out[j + 1], out.back(), q, &x)) {
          if (points) *points += out.size() - (j + 1);
          if (loops) ++*loops;
          out.resize(j + 1);
          out.push_back(x);
          break;
        }
      }
    }
    out.push_back(q);
  }
  return out;
}

std::size_t remove_cusps(std::vector<Eigen::Vector3d>* points, std::vector<Eigen::Vector2d>* uv) {
  std::size_t removed = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 1; i + 1 < points->size(); ++i) {
      const Eigen::Vector3d a = (*points)[i] - (*points)[i - 1], b = (*points)[i + 1] - (*points)[i];
      if (a.dot(b) < 0.0 || a.norm() < 1e-9) {
        points->erase(points->begin() + static_cast<long>(i));
        uv->erase(uv->begin() + static_cast<long>(i));
        ++removed;
        changed = true;
        break;
      }
    }
  }
  return removed;
}

bool self_intersects(const std::vector<Eigen::Vector2d>& polyline) {
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    for (std::size_t j = i + 2; j + 1 < polyline.size(); ++j) {
      if (segments_cross(polyline[i], polyline[i + 1], polyline[j], polyline[j + 1], nullptr)) return true;
    }
  }
  return false;
}

double spacing_error_pct_max(const ParametricSurface& surface, const SurfacePath& from, const SurfacePath& to,
                             const std::function<bool(const Eigen::Vector2d&)>& counted) {
  if (to.uv.size() < 2 || from.spacing_mm.size() != from.uv.size()) return -1.0;
  const ParameterCurve curve{to.uv};
  constexpr int kDensify = 8;
  std::vector<Eigen::Vector3d> dense;
  for (std::size_t k = 0; k + 1 < to.uv.size(); ++k) {
    for (int s = 0; s < kDensify; ++s) {
      Eigen::Vector2d x, d1, d2;
      curve.eval(static_cast<double>(k) + s / double(kDensify), &x, &d1, &d2);
      dense.push_back(surface.position(x.x(), x.y()));
    }
  }
  dense.push_back(to.points.back());
  double worst = -1.0;
  for (std::size_t i = 0; i < from.uv.size(); ++i) {
    if (counted && !counted(from.uv[i])) continue;
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_k = 0;
    for (std::size_t k = 0; k + 1 < dense.size(); ++k) {
      const double d = distance_to_segment(from.points[i], dense[k], dense[k + 1]);
      if (d < best) best = d, best_k = k;
    }
    const bool at_end = (best_k == 0 && (from.points[i] - dense[0]).norm() <= best * (1 + 1e-12)) ||
                        (best_k + 2 == dense.size() && (from.points[i] - dense.back()).norm() <= best * (1 + 1e-12));
    if (at_end) continue;
    worst = std::max(worst, std::abs(best - from.spacing_mm[i]) / from.spacing_mm[i] * 100.0);
  }
  return worst;
}

namespace {

// Cumulative arc length along the path's points.
std::vector<double> arc_lengths(const SurfacePath& path) {
  std::vector<double> s(path.points.size(), 0.0);
  for (std::size_t i = 1; i < s.size(); ++i) s[i] = s[i - 1] + (path.points[i] - path.points[i - 1]).norm();
  return s;
}

// The direction of travel at each point: the parameter chord between the points about `reach` mm before and after
// it (one-sided at the ends). Immediate neighbours a fraction of a millimetre apart would pass on every ripple of
// the path to the next one, amplified: the offset moves a point along the path by g times the direction's error.
std::vector<Eigen::Vector2d> travel_directions(const SurfacePath& path, double reach) {
  const std::vector<double> s = arc_lengths(path);
  const std::size_t n = s.size();
  std::vector<Eigen::Vector2d> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t lo = i, hi = i;
    while (lo > 0 && s[i] - s[lo] < reach) --lo;
    while (hi + 1 < n && s[hi] - s[i] < reach) ++hi;
    out[i] = path.uv[hi] - path.uv[lo];
  }
  return out;
}

// Eq. (5) at every point, then averaged over +-dc/2 along the path: a bead cannot follow the curvature below its
// own width, and the raw values would make the next path ripple (the same amplification as above).
std::vector<double> smoothed_targets(const ParametricSurface& surface, const SurfacePath& path,
                                     const std::vector<Eigen::Vector2d>& directions, const ParallelPathOptions& options) {
  const std::size_t n = path.uv.size();
  std::vector<double> raw(n, options.spacing_mm);
  for (std::size_t i = 0; i < n; ++i) {
    const FundamentalForms f = fundamental_forms(surface, path.uv[i].x(), path.uv[i].y());
    const double up = directions[i].x(), vp = directions[i].y();
    const double speed = std::sqrt(f.first(up, vp)), H = std::sqrt(std::max(f.E * f.G - f.F * f.F, 0.0));
    if (!(speed > 0.0) || !(H > 0.0)) continue;
    const Eigen::Vector2d across = Eigen::Vector2d(-(f.F * up + f.G * vp), f.E * up + f.F * vp) / (H * speed);
    raw[i] = lateral_spacing(options.spacing_mm, options.torch_distance_mm,
                             options.normal_sign * f.normal_curvature(across.x(), across.y()));
  }
  const std::vector<double> s = arc_lengths(path);
  std::vector<double> out(n), prefix(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + raw[i];
  std::size_t lo = 0, hi = 0;  // the window [lo, hi) of points within dc/2 of s[i] (s is increasing)
  for (std::size_t i = 0; i < n; ++i) {
    while (s[i] - s[lo] > 0.5 * options.spacing_mm) ++lo;
    while (hi < n && s[hi] - s[i] <= 0.5 * options.spacing_mm) ++hi;
    out[i] = (prefix[hi] - prefix[lo]) / static_cast<double>(hi - lo);
  }
  return out;
}

// The longest run of offset points inside the domain, each end extended to where the parameter segment to its outside
// neighbour crosses the domain's border: a path that leaves the surface ends at its edge, not one step before it.
std::vector<Eigen::Vector2d> clip_to_domain(const std::vector<Eigen::Vector2d>& points, const std::vector<bool>& inside,
                                            const ParameterDomain& d) {
  auto crossing = [&](const Eigen::Vector2d& in, const Eigen::Vector2d& out) {
    double t = 1.0;  // largest t in [0, 1] with in + t (out - in) in the domain
    const Eigen::Vector2d step = out - in;
    const double lo[2] = {d.u_min, d.v_min}, hi[2] = {d.u_max, d.v_max};
    for (int a = 0; a < 2; ++a) {
      if (step[a] > 0.0) t = std::min(t, (hi[a] - in[a]) / step[a]);
      if (step[a] < 0.0) t = std::min(t, (lo[a] - in[a]) / step[a]);
    }
    return Eigen::Vector2d(in + std::max(t, 0.0) * step);
  };
  std::vector<Eigen::Vector2d> best, run;
  for (std::size_t i = 0; i <= points.size(); ++i) {
    if (i < points.size() && inside[i]) {
      if (run.empty() && i > 0) run.push_back(crossing(points[i], points[i - 1]));
      run.push_back(points[i]);
      continue;
    }
    if (!run.empty()) {
      if (i < points.size()) run.push_back(crossing(points[i - 1], points[i]));
      if (run.size() > best.size()) best = run;
      run.clear();
    }
  }
  return best;
}

}  // namespace

ParallelPathResult parallel_paths(const ParametricSurface& surface, const std::vector<Eigen::Vector2d>& reference,
                                  const ParallelPathOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error("parallel paths: " + error);
  if (reference.size() < 2) throw Error("parallel paths: the reference path needs at least 2 points");
  ParallelPathResult result;
  std::vector<Eigen::Vector2d> polyline = reference;
  for (int n = 0; n < options.max_paths; ++n) {
    SurfacePath path = step_along(surface, polyline, options, &result.chord_error_mm_max);
    // The smooth interpolant can overshoot at a cut loop's corner into a small loop of its own: cut that too.
    std::size_t loops = 0;
    path.uv = remove_loops(path.uv, &loops, &result.points_in_loops);
    if (loops > 0) {
      result.loops_removed += loops;
      path.points.clear();
      for (const Eigen::Vector2d& uv : path.uv) path.points.push_back(surface.position(uv.x(), uv.y()));
    }
    bool in_region = false;
    for (const Eigen::Vector2d& uv : path.uv) in_region = in_region || options.region.contains(uv.x(), uv.y());
    if (!in_region) {
      result.termination = "the next path left the region";
      result.ok = true;
      return result;
    }
    std::vector<Eigen::Vector2d> offsets;
    std::vector<bool> inside;
    const std::vector<Eigen::Vector2d> directions = travel_directions(path, 0.5 * options.spacing_mm);
    path.spacing_mm = smoothed_targets(surface, path, directions, options);
    for (std::size_t i = 0; i < path.uv.size(); ++i) {
      Eigen::Vector2d x;
      bool exact = false;
      const bool in = offset_point_by(surface, path.uv[i], directions[i], options, &x, &path.spacing_mm[i], &exact);
      if (!x.allFinite()) continue;
      offsets.push_back(x);
      inside.push_back(in);
      if (exact) ++result.newton_offsets;
    }
    result.paths.push_back(std::move(path));
    const std::vector<Eigen::Vector2d> next = clip_to_domain(offsets, inside, surface.domain());
    polyline = remove_loops(next, &result.loops_removed, &result.points_in_loops);
    if (polyline.size() < 2) {
      result.termination = "the next path left the surface";
      result.ok = true;
      return result;
    }
  }
  result.termination = "max_paths reached";
  result.ok = true;
  return result;
}

}  // namespace conform
