#include "conform/datasets/panel.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/datasets/panel_shape.h"
#include "conform/core/random.h"

namespace conform {
namespace {

constexpr double kEdgeStepMm = 0.05;  // dense edge sampling; far finer than any output spacing

struct Edge {
  std::vector<OpeningSample> samples;
  double total_tau = 0.0;
};

Edge make_edge(const PanelOptions& o) {
  Edge e;
  e.samples = opening_edge(o, kEdgeStepMm);
  const OpeningSample& last = e.samples.back();
  const OpeningSample& first = e.samples.front();
  double turn = std::abs(std::atan2(first.m.y(), first.m.x()) - std::atan2(last.m.y(), last.m.x()));
  if (turn > M_PI) turn = 2.0 * M_PI - turn;
  e.total_tau = last.tau + (first.q - last.q).norm() + 0.5 * o.band_mm * turn;
  return e;
}

// Whether p, in the plane of the triangle a b c, lies inside it (its barycentric coordinates, to 1e-9).
bool inside_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - a, v = c - a, w = p - a;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), wu = w.dot(u), wv = w.dot(v);
  const double det = uu * vv - uv * uv;
  if (!(det > 0.0)) return false;
  const double beta = (vv * wu - uv * wv) / det, gamma = (uu * wv - uv * wu) / det;
  return beta >= -1e-9 && gamma >= -1e-9 && beta + gamma <= 1.0 + 1e-9;
}

// The band (rows 0..rows outwards from the edge) and the flank (rows 1..flank_rows down the edge) on a grid of
// columns at even tau; each vertex remembers its column's tau and its distance from the edge (0 on the flank).
struct SurfaceGrid {
  Mesh mesh;
  std::vector<double> tau, depth_from_edge;
  std::vector<bool> flank_face;
};

SurfaceGrid make_surface(const PanelOptions& o, const Edge& edge) {
  const int columns = std::max(16, static_cast<int>(std::ceil(edge.total_tau / o.surface_edge_mm)));
  const int rows = std::max(1, static_cast<int>(std::ceil(o.band_mm / o.surface_edge_mm)));
  const int flank_rows = std::max(1, static_cast<int>(std::ceil(o.thickness_mm / o.surface_edge_mm)));
  const int per_column = rows + 1 + flank_rows;
  SurfaceGrid g;
  for (int j = 0; j < columns; ++j) {
    const double tau = edge.total_tau * j / columns;
    const OpeningSample s = edge_at(edge.samples, edge.total_tau, tau);
    for (int i = 0; i <= rows; ++i) {
      const double d = o.band_mm * i / rows;
      g.mesh.vertices.push_back(panel_surface(o, s.q + d * s.m));
      g.tau.push_back(tau);
      g.depth_from_edge.push_back(d);
    }
    const Eigen::Vector3d rim = panel_surface(o, s.q);
    const Eigen::Vector3d n = panel_normal(o, s.q);
    for (int k = 1; k <= flank_rows; ++k) {
      g.mesh.vertices.push_back(rim - o.thickness_mm * k / flank_rows * n);
      g.tau.push_back(tau);
      g.depth_from_edge.push_back(0.0);
    }
  }
  const auto index = [&](int j, int r) { return static_cast<std::int32_t>((j % columns) * per_column + r); };
  // Flank row k (0 the rim) is grid row 0 for k = 0, rows + k otherwise.
  const auto flank = [&](int j, int k) { return k == 0 ? index(j, 0) : index(j, rows + k); };
  for (int j = 0; j < columns; ++j) {
    for (int i = 0; i < rows; ++i) {  // normals along the surface normal (panel_shape.cpp: tau runs counter-clockwise)
      g.mesh.faces.push_back({index(j, i), index(j, i + 1), index(j + 1, i)});
      g.mesh.faces.push_back({index(j + 1, i), index(j, i + 1), index(j + 1, i + 1)});
      g.flank_face.insert(g.flank_face.end(), 2, false);
    }
    for (int k = 0; k < flank_rows; ++k) {  // normals into the opening
      g.mesh.faces.push_back({flank(j, k), flank(j + 1, k), flank(j, k + 1)});
      g.mesh.faces.push_back({flank(j + 1, k), flank(j + 1, k + 1), flank(j, k + 1)});
      g.flank_face.insert(g.flank_face.end(), 2, true);
    }
  }
  return g;
}

// The opening's top edge resampled by its 3D length at even spacing; also the length.
std::vector<OpeningSample> resample_edge(const PanelOptions& o, const Edge& edge, double spacing, double* length) {
  std::vector<double> s{0.0};
  std::vector<Eigen::Vector3d> rim;
  for (const OpeningSample& e : edge.samples) rim.push_back(panel_surface(o, e.q));
  for (std::size_t i = 1; i <= rim.size(); ++i) s.push_back(s.back() + (rim[i % rim.size()] - rim[i - 1]).norm());
  *length = s.back();
  const int n = std::max(8, static_cast<int>(std::lround(*length / spacing)));
  std::vector<OpeningSample> out;
  std::size_t i = 0;
  for (int k = 0; k < n; ++k) {
    const double target = *length * k / n;
    while (s[i + 1] < target) ++i;
    const OpeningSample& a = edge.samples[i];
    const OpeningSample& b = edge.samples[(i + 1) % edge.samples.size()];
    const double f = s[i + 1] > s[i] ? (target - s[i]) / (s[i + 1] - s[i]) : 0.0;
    out.push_back({a.q + f * (b.q - a.q), (a.m + f * (b.m - a.m)).normalized(), a.tau + f * (b.tau - a.tau)});
  }
  return out;
}

void make_paths(const PanelOptions& o, const Edge& edge, PanelData& data) {
  for (const OpeningSample& s : resample_edge(o, edge, o.contour_spacing_mm, &data.perimeter_mm)) {
    data.contour.points.push_back(panel_surface(o, s.q));
  }
  data.contour.closed = true;
  double length = 0.0;
  for (const OpeningSample& s : resample_edge(o, edge, o.trajectory_spacing_mm, &length)) {
    const Eigen::Vector3d p = panel_surface(o, s.q);
    const Eigen::Vector3d n = panel_normal(o, s.q);
    data.trajectory.points.push_back(p);
    data.trajectory.normals.push_back(n);
    data.truth.points.push_back(deform_point(o, p));
    data.truth.normals.push_back(deform_normal(o, p, n));
  }
}

std::vector<std::pair<double, double>> missing_arcs(const PanelOptions& o, double total_tau, Random& random) {
  std::vector<std::pair<double, double>> arcs;
  if (o.missing_fraction <= 0.0) return arcs;
  const double sector = total_tau / o.missing_patches;
  const double length = o.missing_fraction * total_tau / o.missing_patches;  // <= 0.9 sector: arcs cannot overlap
  for (int k = 0; k < o.missing_patches; ++k)
    arcs.emplace_back(sector * k + random.uniform(0.0, sector - length), length);
  return arcs;
}

bool in_arc(const std::vector<std::pair<double, double>>& arcs, double tau) {
  for (const auto& [start, length] : arcs) {
    if (tau >= start && tau < start + length) return true;
  }
  return false;
}

// Area-uniform points on the nominal surface, deformed, with Gaussian noise along the deformed normal; the points in
// missing arcs (near the edge) and holes are left out, and so is the flank of a one-sided scan. A stray point is
// moved 1-20 mm along the normal, either way.
void make_scan(const PanelOptions& o, const SurfaceGrid& g, double total_tau, PanelData& data) {
  Random pick(o.seed, 1), noise(o.seed, 2), layout(o.seed, 3), stray(o.seed, 4);
  data.missing_arcs = missing_arcs(o, total_tau, layout);
  std::vector<Eigen::Vector3d> hole_centres;
  for (int h = 0; h < o.holes; ++h) hole_centres.push_back(g.mesh.vertices[layout.below(g.mesh.vertices.size())]);
  std::vector<double> cumulative;
  double area = 0.0;
  for (std::size_t f = 0; f < g.mesh.faces.size(); ++f) cumulative.push_back(area += face_area(g.mesh, f));
  const std::int64_t count = o.scan_points > 0 ? o.scan_points : default_scan_points(o.shape);
  const double stripe_angle = o.stripe_angle_deg / kDegPerRad;
  const Eigen::Vector3d stripe_normal(std::cos(stripe_angle), std::sin(stripe_angle), 0.0);
  for (std::int64_t k = 0; k < count; ++k) {
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), pick.uniform() * area);
    const std::size_t f =
        std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
    double u = pick.uniform(), v = pick.uniform();
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const Face& t = g.mesh.faces[f];
    const auto V = [&](int c) { return g.mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])]; };
    Eigen::Vector3d p = V(0) + u * (V(1) - V(0)) + v * (V(2) - V(0));
    // Along the face's plane to the nearest stripe (d . p changes, the face holds). A point that would leave its face
    // is dropped: beyond the face its plane is not the surface (on a curved flank, millimetres off it), and a stripe
    // lies where its plane cuts the surface. A face nearly parallel to the stripes' planes: no stripe crosses it.
    bool across_stripes = false;
    if (o.stripe_spacing_mm > 0.0) {
      const Eigen::Vector3d n = face_normal(g.mesh, f);
      const Eigen::Vector3d along = stripe_normal - n.dot(stripe_normal) * n;
      across_stripes = along.dot(stripe_normal) < 0.1;
      const double s = p.dot(stripe_normal);
      const double stripe = std::round(s / o.stripe_spacing_mm) * o.stripe_spacing_mm;
      if (!across_stripes) {
        p += (stripe - s) / along.dot(stripe_normal) * along;
        across_stripes = !inside_triangle(p, V(0), V(1), V(2));
      }
    }
    const double z = noise.normal();  // drawn for every point, so that holes do not shift the others' noise
    const bool is_stray = stray.uniform() < o.stray_fraction;
    const double offset = (stray.uniform() < 0.5 ? -1.0 : 1.0) * stray.uniform(1.0, 20.0);
    const auto v0 = static_cast<std::size_t>(t[0]);
    bool removed = in_arc(data.missing_arcs, g.tau[v0]) && g.depth_from_edge[v0] <= o.missing_depth_mm;
    removed = removed || (!o.scan_flank && g.flank_face[f]) || across_stripes;
    for (const Eigen::Vector3d& c : hole_centres) removed = removed || (p - c).norm() < o.hole_radius_mm;
    if (removed) {
      ++data.scan_points_removed;
      continue;
    }
    const Eigen::Vector3d n = deform_normal(o, p, face_normal(g.mesh, f));
    const Eigen::Vector3d q = deform_point(o, p) + (o.noise_mm * z + (is_stray ? offset : 0.0)) * n;
    data.scan.points.push_back(
        pcl::PointXYZ(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())));
  }
}

}  // namespace

PanelData generate_panel(const PanelOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("panel options: " + why);
  PanelData data;
  data.options = options;
  data.options.progress = nullptr;
  report(options.progress, "panel: surface", 0.0);
  const Edge edge = make_edge(options);
  SurfaceGrid grid = make_surface(options, edge);
  make_paths(options, edge, data);
  report(options.progress, "panel: surface", 1.0);
  report(options.progress, "panel: scan", 0.0);
  make_scan(options, grid, edge.total_tau, data);
  report(options.progress, "panel: scan", 1.0);
  data.surface = std::move(grid.mesh);
  return data;
}

}  // namespace conform
