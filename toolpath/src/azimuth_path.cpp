#include "conform/toolpath/azimuth_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "conform/core/error.h"
#include "conform/fitting/bspline_fit.h"

namespace conform {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 2.0 * kPi;

double cross_z(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.x() * b.y() - a.y() * b.x(); }
double turn(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(cross_z(a, b), a.x() * b.x() + a.y() * b.y());
}
double azimuth_0_2pi(const Eigen::Vector3d& p) {
  const double a = std::atan2(p.y(), p.x());
  return a < 0.0 ? a + kTwoPi : a;
}

// Keeps the points whose azimuth advances; fails (1h) on a step back farther than the tolerance, (1i) when the turn
// is not exactly one. `points` must start at the smallest azimuth.
AzimuthOrder unwrap(const std::vector<Eigen::Vector3d>& points, double tolerance_mm) {
  AzimuthOrder order;
  order.points.push_back(points[0]);
  order.azimuth_rad.push_back(azimuth_0_2pi(points[0]));
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double step = turn(order.points.back(), points[i]);
    if (step > 0.0) {
      order.points.push_back(points[i]);
      order.azimuth_rad.push_back(order.azimuth_rad.back() + step);
      continue;
    }
    const double back_mm = -step * points[i].head<2>().norm();
    if (back_mm > tolerance_mm) {
      std::ostringstream what;
      what << "the curve is not parameterisable by azimuth: it runs back " << back_mm << " mm around the stub axis";
      order.check = curve_failure("1h", what.str(), points[i]);
      return order;
    }
    ++order.dropped;
  }
  const double total =
      order.azimuth_rad.back() + turn(order.points.back(), order.points.front()) - order.azimuth_rad.front();
  if (std::abs(total - kTwoPi) > 1e-6) {
    std::ostringstream what;
    what << "the curve turns " << total * 180.0 / kPi
         << " deg about the stub axis, not once around it (its projection on the stub x-y plane does not enclose "
            "the axis)";
    order.check = curve_failure("1i", what.str(), points[0]);
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

AzimuthOrder order_by_azimuth(const IntersectionGraph& graph, double backtrack_tolerance_mm) {
  const std::size_t n = graph.vertices.size();
  std::vector<std::vector<std::int32_t>> neighbours(n);
  for (const auto& e : graph.edges) {
    neighbours[static_cast<std::size_t>(e[0])].push_back(e[1]);
    neighbours[static_cast<std::size_t>(e[1])].push_back(e[0]);
  }
  std::size_t start = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (graph.vertices[v].head<2>().norm() == 0.0) {
      AzimuthOrder order;
      order.check = curve_failure("1g", "a vertex lies on the stub axis (no azimuth)", graph.vertices[v]);
      return order;
    }
    if (azimuth_0_2pi(graph.vertices[v]) < azimuth_0_2pi(graph.vertices[start])) start = v;
  }
  // Algorithm 1: the direction is the neighbour v' with sgn(z . (v x v')) > 0. Neighbours at v's own azimuth
  // (coincident crossings where a vertex lies on the other mesh) decide nothing: look further along.
  const Eigen::Vector3d& v = graph.vertices[start];
  const auto first_turn = [&](std::int32_t towards) {
    auto before = static_cast<std::int32_t>(start);
    for (std::size_t steps = 0; steps < n && towards != static_cast<std::int32_t>(start); ++steps) {
      const double turn_z = cross_z(v, graph.vertices[static_cast<std::size_t>(towards)]);
      if (turn_z != 0.0) return turn_z;
      const auto& around = neighbours[static_cast<std::size_t>(towards)];
      const std::int32_t after = around[0] == before ? around[1] : around[0];
      before = towards;
      towards = after;
    }
    return 0.0;
  };
  std::int32_t next = neighbours[start][0];
  if (first_turn(next) < 0.0) next = neighbours[start][1];
  std::vector<Eigen::Vector3d> walk{v};
  auto previous = static_cast<std::int32_t>(start);
  while (next != static_cast<std::int32_t>(start) && walk.size() <= n) {
    walk.push_back(graph.vertices[static_cast<std::size_t>(next)]);
    const auto& around = neighbours[static_cast<std::size_t>(next)];
    const std::int32_t after = around[0] == previous ? around[1] : around[0];
    previous = next;
    next = after;
  }
  return unwrap(walk, backtrack_tolerance_mm);
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
