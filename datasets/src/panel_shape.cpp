#include "conform/datasets/panel_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace conform {
namespace {

double angle_of(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

// Appends samples from the last one to (q, m), adding tau for the length moved and the turn of m.
void append(std::vector<OpeningSample>& edge, const Eigen::Vector2d& q, const Eigen::Vector2d& m, double band) {
  OpeningSample s{q, m.normalized(), 0.0};
  if (!edge.empty()) {
    const OpeningSample& last = edge.back();
    double turn = std::abs(angle_of(s.m) - angle_of(last.m));
    if (turn > M_PI) turn = 2.0 * M_PI - turn;
    s.tau = last.tau + (q - last.q).norm() + 0.5 * band * turn;
  }
  edge.push_back(s);
}

std::vector<OpeningSample> ellipse_edge(const PanelOptions& o, double step) {
  const double a = 0.5 * o.porthole_width_mm;
  const double b = o.round ? a : 0.5 * o.porthole_height_mm;
  const Eigen::Vector2d c(o.porthole_x_mm, o.porthole_y_mm);
  const double perimeter = M_PI * (3.0 * (a + b) - std::sqrt((3.0 * a + b) * (a + 3.0 * b)));  // Ramanujan
  const int n = std::max(180, static_cast<int>(std::ceil(perimeter / step)));
  std::vector<OpeningSample> edge;
  for (int i = 0; i < n; ++i) {
    const double phi = 2.0 * M_PI * i / n;
    append(edge, c + Eigen::Vector2d(a * std::cos(phi), b * std::sin(phi)),
           Eigen::Vector2d(b * std::cos(phi), a * std::sin(phi)), o.band_mm);
  }
  return edge;
}

// A convex polygon, counter-clockwise, with corners rounded to radius r: straight edges between arcs about the
// corners of the polygon shrunk by r. r = 0 leaves fans (the same point, m turning) at the corners.
std::vector<OpeningSample> rounded_polygon_edge(const PanelOptions& o, const std::array<Eigen::Vector2d, 4>& v,
                                                double step) {
  std::array<Eigen::Vector2d, 4> normal;  // outward of edge k = v[k] -> v[k+1]
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d t = (v[static_cast<std::size_t>((k + 1) % 4)] - v[static_cast<std::size_t>(k)]).normalized();
    normal[static_cast<std::size_t>(k)] = Eigen::Vector2d(t.y(), -t.x());
  }
  const double r = o.corner_radius_mm;
  std::array<Eigen::Vector2d, 4> centre;  // arc centre of corner k (between edges k-1 and k)
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d& n1 = normal[static_cast<std::size_t>((k + 3) % 4)];
    const Eigen::Vector2d& n2 = normal[static_cast<std::size_t>(k)];
    centre[static_cast<std::size_t>(k)] = v[static_cast<std::size_t>(k)] - r * (n1 + n2) / (1.0 + n1.dot(n2));
  }
  std::vector<OpeningSample> edge;
  const double max_turn = 2.0 * M_PI / 180.0;
  for (int k = 0; k < 4; ++k) {
    const auto K = static_cast<std::size_t>(k);
    const Eigen::Vector2d& from_n = normal[(K + 3) % 4];
    const Eigen::Vector2d& to_n = normal[K];
    double turn = angle_of(to_n) - angle_of(from_n);
    while (turn < 0.0) turn += 2.0 * M_PI;
    const int arc_steps = std::max(2, static_cast<int>(std::ceil(std::max(r * turn / step, turn / max_turn))));
    for (int i = 0; i < arc_steps; ++i) {  // the corner's arc (or fan), without its end
      const double a = angle_of(from_n) + turn * i / arc_steps;
      const Eigen::Vector2d m(std::cos(a), std::sin(a));
      append(edge, centre[K] + r * m, m, o.band_mm);
    }
    const Eigen::Vector2d p0 = centre[K] + r * to_n;
    const Eigen::Vector2d p1 = centre[(K + 1) % 4] + r * to_n;
    const int line_steps = std::max(1, static_cast<int>(std::ceil((p1 - p0).norm() / step)));
    for (int i = 0; i < line_steps; ++i) append(edge, p0 + (p1 - p0) * (double(i) / line_steps), to_n, o.band_mm);
  }
  return edge;
}

std::vector<OpeningSample> window_edge(const PanelOptions& o, double step) {
  const double h = 0.5 * o.window_height_mm;
  return rounded_polygon_edge(
      o,
      {Eigen::Vector2d(-h, -0.5 * o.window_bottom_mm), Eigen::Vector2d(h, -0.5 * o.window_top_mm),
       Eigen::Vector2d(h, 0.5 * o.window_top_mm), Eigen::Vector2d(-h, 0.5 * o.window_bottom_mm)},
      step);
}

std::vector<OpeningSample> cut_out_edge(const PanelOptions& o, double step) {
  const double a = 0.5 * o.porthole_width_mm;
  const double b = o.round ? a : 0.5 * o.porthole_height_mm;
  const Eigen::Vector2d c(o.porthole_x_mm, o.porthole_y_mm);
  return rounded_polygon_edge(
      o,
      {c + Eigen::Vector2d(-a, -b), c + Eigen::Vector2d(a, -b), c + Eigen::Vector2d(a, b), c + Eigen::Vector2d(-a, b)},
      step);
}

// A number in [-1, 1] from (seed, index): splitmix64, so that the field needs no state per call.
double field_hash(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + (index + 1) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return 2.0 * static_cast<double>(z >> 11) / 9007199254740992.0 - 1.0;
}

// The smooth field: per axis three plane waves a sin(2 pi (u . p) / lambda + phi) over the panel's (x, y), with
// sum |a| = 1 so that the axis' bound holds (field_mm along z, half of it along x and y).
Eigen::Vector3d smooth_field(const PanelOptions& o, const Eigen::Vector3d& p) {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  if (o.field_mm == 0.0) return d;
  const std::uint64_t seed = o.seed ^ 0x5EEDF1E1Dull;
  for (int axis = 0; axis < 3; ++axis) {
    double a[3], sum = 0.0;
    for (int j = 0; j < 3; ++j) sum += std::abs(a[j] = field_hash(seed, static_cast<std::uint64_t>(10 * axis + j)));
    for (int j = 0; j < 3; ++j) {
      const auto key = static_cast<std::uint64_t>(100 + 10 * axis + j);
      const double direction = M_PI * field_hash(seed, key);
      const double lambda = o.field_wavelength_mm * (1.5 + 0.5 * field_hash(seed, key + 1000));
      const double phase = M_PI * field_hash(seed, key + 2000);
      const double u = std::cos(direction) * p.x() + std::sin(direction) * p.y();
      d(axis) += a[j] / std::max(sum, 1e-12) * std::sin(2.0 * M_PI * u / lambda + phase);
    }
  }
  return o.field_mm * Eigen::Vector3d(0.5 * d.x(), 0.5 * d.y(), d.z());
}

// The dent's centre on the opening (panel_options.h: dent_at), in the parameter plane: on the ellipse at that parameter
// angle, on the rectangle and the nose cone's trapezoid where the ray from the opening's centre meets its sides (the
// rounded corners left aside).
Eigen::Vector2d dent_centre(const PanelOptions& o) {
  const double t = 2.0 * M_PI * o.dent_at;
  const Eigen::Vector2d d(std::cos(t), std::sin(t));
  if (o.shape == PanelShape::kNoseCone) {
    const double h = 0.5 * o.window_height_mm;
    const std::array<Eigen::Vector2d, 4> v = {Eigen::Vector2d(-h, -0.5 * o.window_bottom_mm),
                                              Eigen::Vector2d(h, -0.5 * o.window_top_mm),
                                              Eigen::Vector2d(h, 0.5 * o.window_top_mm),
                                              Eigen::Vector2d(-h, 0.5 * o.window_bottom_mm)};
    double reach = 1e300;
    for (std::size_t k = 0; k < 4; ++k) {
      const Eigen::Vector2d side = v[(k + 1) % 4] - v[k];
      const Eigen::Vector2d outward(side.y(), -side.x());
      if (outward.dot(d) > 1e-12) reach = std::min(reach, outward.dot(v[k]) / outward.dot(d));
    }
    return reach * d;
  }
  const double a = 0.5 * o.porthole_width_mm, b = o.round ? a : 0.5 * o.porthole_height_mm;
  if (o.opening == PlateOpening::kEllipse) return {o.porthole_x_mm + a * d.x(), o.porthole_y_mm + b * d.y()};
  const double reach = std::min(std::abs(d.x()) > 1e-12 ? a / std::abs(d.x()) : 1e300,
                                std::abs(d.y()) > 1e-12 ? b / std::abs(d.y()) : 1e300);
  return Eigen::Vector2d(o.porthole_x_mm, o.porthole_y_mm) + reach * d;
}

// The dent's depth at the parameter point q (Gaussian, sigma a quarter of the full width); 0 without a dent.
double dent_depth_at(const PanelOptions& o, const Eigen::Vector2d& q) {
  if (o.dent_depth_mm == 0.0) return 0.0;
  const double sigma = 0.25 * o.dent_width_mm;
  return o.dent_depth_mm * std::exp(-(q - dent_centre(o)).squaredNorm() / (2.0 * sigma * sigma));
}

// Normalised deflection of a uniformly loaded simply supported beam, 1 at mid-span, 0 at the supports.
double beam(double xi) { return 16.0 / 5.0 * (xi - 2.0 * xi * xi * xi + xi * xi * xi * xi); }

Eigen::Vector3d displacement(const PanelOptions& o, const Eigen::Vector3d& p) {
  if (o.shape == PanelShape::kPlate) {
    const double xi = p.x() / o.clamp_span_mm + 0.5;
    const double u = 2.0 * p.x() / o.clamp_span_mm;
    const double v = 2.0 * (p.y() - o.porthole_y_mm) / (o.round ? o.porthole_width_mm : o.porthole_height_mm);
    const double dent = dent_depth_at(o, p.head<2>());
    return Eigen::Vector3d(0.0, 0.0, -o.sag_mm * beam(xi) + o.bend_mm * v * v + o.twist_mm * u * v - dent) +
           smooth_field(o, p);
  }
  const double theta = std::atan2(p.y(), p.z());
  const Eigen::Vector3d e_r(0.0, std::sin(theta), std::cos(theta));
  const double front = (p.x() + 0.5 * o.barrel_length_mm) / o.barrel_length_mm;
  const double dent = dent_depth_at(o, Eigen::Vector2d(p.x(), o.barrel_radius_mm * theta));  // into the barrel
  return (o.ovality_mm * std::cos(2.0 * theta) - dent) * e_r - o.droop_mm * front * front * Eigen::Vector3d::UnitZ() +
         smooth_field(o, p);
}

}  // namespace

Eigen::Vector3d panel_surface(const PanelOptions& o, const Eigen::Vector2d& q) {
  if (o.shape == PanelShape::kPlate) {
    return {q.x(), q.y(), q.x() * q.x() / (2.0 * o.plate_radius_x_mm) + q.y() * q.y() / (2.0 * o.plate_radius_y_mm)};
  }
  const double theta = q.y() / o.barrel_radius_mm;
  return {q.x(), o.barrel_radius_mm * std::sin(theta), o.barrel_radius_mm * std::cos(theta)};
}

Eigen::Vector3d panel_normal(const PanelOptions& o, const Eigen::Vector2d& q) {
  if (o.shape == PanelShape::kPlate) {
    return Eigen::Vector3d(-q.x() / o.plate_radius_x_mm, -q.y() / o.plate_radius_y_mm, 1.0).normalized();
  }
  const double theta = q.y() / o.barrel_radius_mm;
  return {0.0, std::sin(theta), std::cos(theta)};
}

std::vector<OpeningSample> opening_edge(const PanelOptions& options, double step_mm) {
  if (options.shape == PanelShape::kNoseCone) return window_edge(options, step_mm);
  return options.opening == PlateOpening::kEllipse ? ellipse_edge(options, step_mm) : cut_out_edge(options, step_mm);
}

OpeningSample edge_at(const std::vector<OpeningSample>& edge, double total_tau, double tau) {
  tau = std::fmod(tau, total_tau);
  if (tau < 0.0) tau += total_tau;
  const auto it =
      std::upper_bound(edge.begin(), edge.end(), tau, [](double t, const OpeningSample& s) { return t < s.tau; });
  const std::size_t i1 = static_cast<std::size_t>(it - edge.begin());  // >= 1: edge[0].tau = 0 <= tau
  const OpeningSample& a = edge[i1 - 1];
  const OpeningSample& b = i1 < edge.size() ? edge[i1] : edge.front();
  const double b_tau = i1 < edge.size() ? b.tau : total_tau;
  const double f = b_tau > a.tau ? (tau - a.tau) / (b_tau - a.tau) : 0.0;
  OpeningSample s;
  s.q = a.q + f * (b.q - a.q);
  s.m = (a.m + f * (b.m - a.m)).normalized();
  s.tau = tau;
  return s;
}

Eigen::Isometry3d panel_rigid_motion(const PanelOptions& o) {
  const Eigen::Vector3d rv = o.rotation_deg * (M_PI / 180.0);
  Eigen::Isometry3d G = Eigen::Isometry3d::Identity();
  if (rv.norm() > 0.0) G.linear() = Eigen::AngleAxisd(rv.norm(), rv.normalized()).toRotationMatrix();
  G.translation() = o.translation_mm;
  return G;
}

Eigen::Vector3d deform_point(const PanelOptions& options, const Eigen::Vector3d& p) {
  return panel_rigid_motion(options) * (p + displacement(options, p));
}

Eigen::Vector3d deform_normal(const PanelOptions& options, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  constexpr double h = 1e-3;  // mm: the field varies over hundreds of mm, so central differences are exact to ~1e-9
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
    J.col(k) = (displacement(options, p + e) - displacement(options, p - e)) / (2.0 * h);
  }
  J += Eigen::Matrix3d::Identity();
  return (panel_rigid_motion(options).linear() * J.inverse().transpose() * n).normalized();
}

}  // namespace conform
