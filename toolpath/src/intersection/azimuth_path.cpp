#include "conform/toolpath/intersection/azimuth_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <limits>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/fitting/bspline_fit.h"

namespace conform {
namespace {

double cross_z(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.x() * b.y() - a.y() * b.x(); }
double turn(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(cross_z(a, b), a.x() * b.x() + a.y() * b.y());
}
double azimuth_0_2pi(const Eigen::Vector3d& p) {
  const double a = std::atan2(p.y(), p.x());
  return a < 0.0 ? a + kTwoPi : a;
}

// Unwraps the azimuth along `points` (one positive turn, starting at the smallest azimuth): keeps the points that
// advance it, drops those behind the azimuth reached so far (or past the start's, one turn later) by at most the
// tolerance, fails [azimuth] farther behind.
AzimuthOrder unwrap(const std::vector<Eigen::Vector3d>& points, double tolerance_mm) {
  AzimuthOrder order;
  order.points.push_back(points[0]);
  order.azimuth_rad.push_back(azimuth_0_2pi(points[0]));
  const double end = order.azimuth_rad.front() + kTwoPi;
  double walked = order.azimuth_rad.front();
  for (std::size_t i = 1; i < points.size(); ++i) {
    walked += turn(points[i - 1], points[i]);
    if (walked > order.azimuth_rad.back() && walked < end) {
      order.points.push_back(points[i]);
      order.azimuth_rad.push_back(walked);
      continue;
    }
    const double behind = walked < end ? order.azimuth_rad.back() - walked : walked - end;
    const double back_mm = behind * points[i].head<2>().norm();
    if (back_mm > tolerance_mm) {
      std::ostringstream what;
      what << "the curve is not parameterisable by azimuth: it runs back " << back_mm
           << " mm around the stub axis (tolerance " << tolerance_mm << " mm)";
      order.check = curve_failure("azimuth", what.str(), points[i]);
      return order;
    }
    order.max_backtrack_mm = std::max(order.max_backtrack_mm, back_mm);
    ++order.dropped;
  }
  return order;
}

// The point at azimuth phi (any value) on the ordered polyline, linearly (Eq. 2).
Eigen::Vector3d at_azimuth(const AzimuthOrder& order, double phi) {
  const double start = order.azimuth_rad.front();
  while (phi < start) phi += kTwoPi;
  while (phi >= start + kTwoPi) phi -= kTwoPi;
  const auto& a = order.azimuth_rad;
  const std::size_t n = a.size();
  const auto it = std::upper_bound(a.begin(), a.end(), phi);
  const std::size_t j = static_cast<std::size_t>(it - a.begin());  // a[j - 1] <= phi < a[j] (j = n: closing span)
  const std::size_t i = j - 1;
  const double a1 = j < n ? a[j] : start + kTwoPi;
  const Eigen::Vector3d& p1 = order.points[j < n ? j : 0];
  const double s = (phi - a[i]) / (a1 - a[i]);
  return order.points[i] + s * (p1 - order.points[i]);
}

AzimuthOrder smooth(const AzimuthOrder& order, double smoothing_mm2, double* rms_mm) {
  BSplineFitOptions fit_options;
  fit_options.closed = true;
  fit_options.parameters = order.azimuth_rad;
  fit_options.parameters.push_back(order.azimuth_rad.front() + kTwoPi);
  fit_options.smoothing_mm2 = smoothing_mm2;
  const BSplineFit fit = fit_bspline_curve(order.points, fit_options);
  *rms_mm = fit.rms_mm;
  const std::size_t dense = std::max<std::size_t>(8 * order.points.size(), 3600);
  std::vector<Eigen::Vector3d> samples(dense);
  for (std::size_t k = 0; k < dense; ++k) {
    samples[k] =
        fit.curve.position(order.azimuth_rad.front() + kTwoPi * static_cast<double>(k) / static_cast<double>(dense));
  }
  const auto first = std::min_element(samples.begin(), samples.end(),
                                      [](const auto& x, const auto& y) { return azimuth_0_2pi(x) < azimuth_0_2pi(y); });
  std::rotate(samples.begin(), first, samples.end());
  return unwrap(samples, 0.0);
}

// The vertices in the order of the graph's cycle, from vertex 0, coincident neighbours merged (counted).
std::vector<Eigen::Vector3d> walk_cycle(const IntersectionGraph& graph, std::size_t* merged) {
  const std::size_t n = graph.vertices.size();
  std::vector<std::vector<std::int32_t>> neighbours(n);
  for (const auto& e : graph.edges) {
    neighbours[static_cast<std::size_t>(e[0])].push_back(e[1]);
    neighbours[static_cast<std::size_t>(e[1])].push_back(e[0]);
  }
  std::vector<Eigen::Vector3d> walk;
  if (n == 0 || neighbours[0].size() != 2) return walk;
  walk.push_back(graph.vertices[0]);
  std::int32_t previous = 0;
  std::int32_t next = neighbours[0][0];
  while (next != 0 && walk.size() <= n) {
    const Eigen::Vector3d& p = graph.vertices[static_cast<std::size_t>(next)];
    if (p == walk.back()) {
      ++*merged;
    } else {
      walk.push_back(p);
    }
    const auto& around = neighbours[static_cast<std::size_t>(next)];
    const std::int32_t after = around[0] == previous ? around[1] : around[0];
    previous = next;
    next = after;
  }
  while (walk.size() > 1 && walk.back() == walk.front()) {
    walk.pop_back();
    ++*merged;
  }
  return walk;
}

// (1h): no two vertices of the cycle at the same coordinates.
CurveCheck check_unique(const std::vector<Eigen::Vector3d>& cycle) {
  std::vector<std::size_t> index(cycle.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
  const auto less = [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(cycle[a].data(), cycle[a].data() + 3, cycle[b].data(), cycle[b].data() + 3);
  };
  std::sort(index.begin(), index.end(), less);
  for (std::size_t i = 1; i < index.size(); ++i) {
    if (cycle[index[i]] == cycle[index[i - 1]]) {
      return curve_failure("1h", "two vertices of the curve coincide (it touches itself)", cycle[index[i]]);
    }
  }
  return {};
}

// A closed smoothing cubic B-spline over the cycle, parameterised by chord length, sampled densely.
std::vector<Eigen::Vector3d> smooth_cycle(const std::vector<Eigen::Vector3d>& cycle, double smoothing_mm2,
                                          double* rms_mm) {
  BSplineFitOptions fit_options;
  fit_options.closed = true;
  fit_options.parameters.push_back(0.0);
  for (std::size_t i = 1; i <= cycle.size(); ++i) {
    fit_options.parameters.push_back(fit_options.parameters.back() +
                                     (cycle[i % cycle.size()] - cycle[i - 1]).norm());
  }
  fit_options.smoothing_mm2 = smoothing_mm2;
  const BSplineFit fit = fit_bspline_curve(cycle, fit_options);
  *rms_mm = fit.rms_mm;
  const double length = fit_options.parameters.back();
  const std::size_t dense = std::max<std::size_t>(8 * cycle.size(), 3600);
  std::vector<Eigen::Vector3d> samples(dense);
  for (std::size_t k = 0; k < dense; ++k) {
    samples[k] = fit.curve.position(length * static_cast<double>(k) / static_cast<double>(dense));
  }
  return samples;
}

}  // namespace

bool PathSamplingOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (spacing == PathSpacing::kAzimuth && !(step_rad > 0.0 && step_rad <= kPi / 2)) {
    why << "azimuth step " << step_rad * 180.0 / kPi << " deg is outside (0, 90] deg";
  } else if (spacing == PathSpacing::kArcLength && !(std::isfinite(step_mm) && step_mm > 0.0)) {
    why << "arc-length step " << step_mm << " mm must be > 0";
  } else if (!std::isfinite(smoothing_mm2)) {
    why << "smoothing " << smoothing_mm2 << " mm^2 must be finite (< 0: none)";
  } else if (!(std::isfinite(smoothing_rms_mm) && smoothing_rms_mm >= 0.0)) {
    why << "smoothing RMS " << smoothing_rms_mm << " mm must be >= 0";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

bool AzimuthOrderOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(std::isfinite(backtrack_tolerance_mm) && backtrack_tolerance_mm >= 0.0)) {
    why << "backtrack tolerance " << backtrack_tolerance_mm << " mm must be >= 0";
  } else if (!std::isfinite(smoothing_mm2)) {
    why << "smoothing " << smoothing_mm2 << " mm^2 must be finite (< 0: none)";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

AzimuthOrder order_by_azimuth(const IntersectionGraph& graph, double backtrack_tolerance_mm) {
  AzimuthOrderOptions options;
  options.backtrack_tolerance_mm = backtrack_tolerance_mm;
  return order_by_azimuth(graph, options);
}

AzimuthOrder order_by_azimuth(const IntersectionGraph& graph, const AzimuthOrderOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("azimuth order: " + why);
  std::size_t merged = 0;
  std::vector<Eigen::Vector3d> cycle = walk_cycle(graph, &merged);
  AzimuthOrder failure;
  if (cycle.size() < 3) {
    failure.check = curve_failure("1a", "the intersection is not a closed curve: fewer than 3 distinct vertices",
                                  cycle.empty() ? Eigen::Vector3d::Zero() : cycle.front());
    return failure;
  }
  failure.check = check_unique(cycle);
  if (!failure.check.ok) return failure;
  bool smoothed = false;
  double smoothing_rms = 0.0;
  if (options.smoothing_mm2 >= 0.0) {
    cycle = smooth_cycle(cycle, options.smoothing_mm2, &smoothing_rms);
    smoothed = true;
  }
  for (const Eigen::Vector3d& p : cycle) {
    if (p.head<2>().norm() == 0.0) {
      failure.check = curve_failure("axis", "a vertex lies on the stub axis (no azimuth)", p);
      return failure;
    }
  }
  double winding = 0.0;
  for (std::size_t i = 0; i < cycle.size(); ++i) winding += turn(cycle[i], cycle[(i + 1) % cycle.size()]);
  if (std::abs(std::abs(winding) - kTwoPi) > 1e-6) {
    std::ostringstream what;
    what << "the curve turns " << winding * 180.0 / kPi
         << " deg about the stub axis, not once around it (its projection on the stub x-y plane does not enclose "
            "the axis)";
    failure.check = curve_failure("jordan", what.str(), cycle.front());
    return failure;
  }
  if (winding < 0.0) std::reverse(cycle.begin(), cycle.end());
  const auto first = std::min_element(cycle.begin(), cycle.end(),
                                      [](const auto& x, const auto& y) { return azimuth_0_2pi(x) < azimuth_0_2pi(y); });
  std::rotate(cycle.begin(), first, cycle.end());
  AzimuthOrder order = unwrap(cycle, options.backtrack_tolerance_mm);
  order.merged = merged;
  order.smoothed = smoothed;
  order.smoothing_rms_mm = smoothing_rms;
  return order;
}

SampledPath sample_path(const AzimuthOrder& input, const PathSamplingOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("path sampling: " + why);
  if (input.points.size() < 3) throw Error("path sampling: the ordered curve has fewer than 3 points");
  SampledPath path;
  AzimuthOrder smoothed;
  const double target = options.smoothing_rms_mm > 0.0 ? static_cast<double>(input.points.size()) *
                                                             options.smoothing_rms_mm * options.smoothing_rms_mm
                                                       : options.smoothing_mm2;
  if (target >= 0.0) {
    smoothed = smooth(input, target, &path.smoothing_rms_mm);
    path.smoothed = true;
    path.check = smoothed.check;
    if (!path.check.ok) return path;
  }
  const AzimuthOrder& order = path.smoothed ? smoothed : input;
  if (options.spacing == PathSpacing::kAzimuth) {
    const auto count = std::max<std::size_t>(3, static_cast<std::size_t>(std::lround(kTwoPi / options.step_rad)));
    for (std::size_t k = 0; k < count; ++k) {
      const double phi = kTwoPi * static_cast<double>(k) / static_cast<double>(count);
      path.phi_rad.push_back(phi);
      path.points.push_back(at_azimuth(order, phi));
    }
  } else {
    // The closed polyline from the toe (phi = 0) round, then equal arc-length steps along it.
    std::vector<Eigen::Vector3d> ring{at_azimuth(order, 0.0)};
    const std::size_t first = static_cast<std::size_t>(
        std::upper_bound(order.azimuth_rad.begin(), order.azimuth_rad.end(), kTwoPi) - order.azimuth_rad.begin());
    for (std::size_t k = 0; k < order.points.size(); ++k) {
      const std::size_t i = (first + k) % order.points.size();
      if ((order.points[i] - ring.back()).norm() > 0.0) ring.push_back(order.points[i]);
    }
    ring.push_back(ring.front());
    std::vector<double> cumulative{0.0};
    for (std::size_t i = 1; i < ring.size(); ++i)
      cumulative.push_back(cumulative.back() + (ring[i] - ring[i - 1]).norm());
    const double length = cumulative.back();
    const auto count = std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(length / options.step_mm)));
    for (std::size_t k = 0; k < count; ++k) {
      const double s = length * static_cast<double>(k) / static_cast<double>(count);
      std::size_t j =
          static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
      j = std::min(j, ring.size() - 1);
      const double span = cumulative[j] - cumulative[j - 1];
      const double u = span > 0.0 ? (s - cumulative[j - 1]) / span : 0.0;
      const Eigen::Vector3d p = ring[j - 1] + u * (ring[j] - ring[j - 1]);
      path.points.push_back(p);
      path.phi_rad.push_back(k == 0 ? 0.0 : azimuth_0_2pi(p));
    }
  }
  path.min_step_mm = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < path.points.size(); ++k) {
    const double step = (path.points[(k + 1) % path.points.size()] - path.points[k]).norm();
    path.length_mm += step;
    path.max_step_mm = std::max(path.max_step_mm, step);
    path.min_step_mm = std::min(path.min_step_mm, step);
  }
  return path;
}

}  // namespace conform
