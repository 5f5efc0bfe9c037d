#include "conform/report/scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace conform::html {
namespace {

void check_per_item(const std::string& name, std::size_t items, std::size_t per_item, const char* what) {
  if (per_item != 0 && per_item != items) {
    throw std::invalid_argument("report scene: " + name + ": " + std::to_string(per_item) + " " + what + " for " +
                                std::to_string(items) + " items");
  }
}

std::size_t items_of(const SceneObject& o) {
  return o.kind == ObjectKind::kMesh ? o.triangles.size() : o.positions.size();
}

std::size_t limit_of(const Scene::Limits& limits, ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kPoints: return limits.max_points;
    case ObjectKind::kMesh: return limits.max_triangles;
    case ObjectKind::kPolyline: return limits.max_line_points;
    case ObjectKind::kArrows: return limits.max_arrows;
  }
  return limits.max_points;
}

const char* unit_of(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kMesh: return "triangles";
    case ObjectKind::kArrows: return "arrows";
    default: return "points";
  }
}

}  // namespace

SceneObject& Scene::add(SceneObject object) {
  for (const SceneObject& o : objects_) {
    if (o.name == object.name) throw std::invalid_argument("report scene: two objects named " + object.name);
  }
  check_per_item(object.name, object.positions.size(), object.colours.size(), "colours");
  object.original_count = items_of(object);
  objects_.push_back(std::move(object));
  return objects_.back();
}

SceneObject& Scene::add_points(const std::string& name, const std::vector<Eigen::Vector3d>& positions, Rgb colour,
                               double size_px) {
  SceneObject& o = add_points(name, positions, std::vector<Rgb>{}, size_px);
  o.colour = colour;
  return o;
}

SceneObject& Scene::add_points(const std::string& name, const std::vector<Eigen::Vector3d>& positions,
                               const std::vector<Rgb>& colours, double size_px) {
  SceneObject o;
  o.name = name;
  o.kind = ObjectKind::kPoints;
  o.positions = positions;
  o.colours = colours;
  o.size_px = size_px;
  return add(std::move(o));
}

SceneObject& Scene::add_mesh(const std::string& name, const std::vector<Eigen::Vector3d>& vertices,
                             const std::vector<Face>& triangles, Rgb colour, double opacity,
                             const std::vector<Rgb>& vertex_colours) {
  SceneObject o;
  o.name = name;
  o.kind = ObjectKind::kMesh;
  o.positions = vertices;
  o.colours = vertex_colours;
  o.colour = colour;
  o.opacity = std::clamp(opacity, 0.0, 1.0);
  o.triangles.reserve(triangles.size());
  for (const Face& f : triangles) {
    for (std::int32_t v : f) {
      if (v < 0 || static_cast<std::size_t>(v) >= vertices.size()) {
        throw std::invalid_argument("report scene: " + name + ": a triangle's vertex index is out of range");
      }
    }
    o.triangles.push_back({static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[1]),
                           static_cast<std::uint32_t>(f[2])});
  }
  return add(std::move(o));
}

SceneObject& Scene::add_mesh(const std::string& name, const Mesh& mesh, Rgb colour, double opacity) {
  return add_mesh(name, mesh.vertices, mesh.faces, colour, opacity);
}

SceneObject& Scene::add_polyline(const std::string& name, const std::vector<Eigen::Vector3d>& points, Rgb colour,
                                 bool closed) {
  SceneObject o;
  o.name = name;
  o.kind = ObjectKind::kPolyline;
  o.positions = points;
  o.colour = colour;
  o.closed = closed;
  return add(std::move(o));
}

SceneObject& Scene::add_polylines(const std::string& name, const std::vector<std::vector<Eigen::Vector3d>>& lines,
                                  Rgb colour) {
  std::vector<Eigen::Vector3d> pairs;
  for (const std::vector<Eigen::Vector3d>& line : lines) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) pairs.push_back(line[i]), pairs.push_back(line[i + 1]);
  }
  SceneObject& o = add_polyline(name, pairs, colour);
  o.pieces = true;
  return o;
}

SceneObject& Scene::add_arrows(const std::string& name, const std::vector<Eigen::Vector3d>& origins,
                               const std::vector<Eigen::Vector3d>& directions, double length_mm, Rgb colour) {
  if (directions.size() != origins.size()) {
    throw std::invalid_argument("report scene: " + name + ": " + std::to_string(directions.size()) +
                                " directions for " + std::to_string(origins.size()) + " origins");
  }
  SceneObject o;
  o.name = name;
  o.kind = ObjectKind::kArrows;
  o.colour = colour;
  o.length_mm = length_mm;
  for (std::size_t i = 0; i < origins.size(); ++i) {
    const double n = directions[i].norm();
    if (!(n > 0.0) || !std::isfinite(n)) continue;
    o.positions.push_back(origins[i]);
    o.directions.push_back(directions[i] / n);
  }
  return add(std::move(o));
}

Eigen::Vector3d Scene::origin() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const SceneObject& o : objects_) {
    for (const Eigen::Vector3d& p : o.positions) {
      if (!p.allFinite()) continue;
      sum += p;
      ++n;
    }
  }
  return n > 0 ? Eigen::Vector3d(sum / static_cast<double>(n)) : Eigen::Vector3d::Zero();
}

std::vector<SceneObject> Scene::thinned() const {
  std::vector<SceneObject> out;
  for (const SceneObject& o : objects_) {
    check_per_item(o.name, o.positions.size(), o.values.size(), "values");
    std::size_t total = 0;
    for (const SceneObject& other : objects_) {
      if (other.kind == o.kind) total += items_of(other);
    }
    const std::size_t limit = limit_of(limits_, o.kind);
    // This object's share of the limit, in proportion to its size.
    const std::size_t share =
        total <= limit ? items_of(o)
                       : std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(limit) *
                                                                          static_cast<double>(items_of(o)) /
                                                                          static_cast<double>(total)));
    out.push_back(o.kind == ObjectKind::kMesh ? thin_mesh(o, share) : thin_by_stride(o, share));
  }
  return out;
}

std::vector<std::string> Scene::notes(const std::vector<SceneObject>& thinned) const {
  std::vector<std::string> notes;
  for (const SceneObject& o : thinned) {
    const std::size_t shown = items_of(o);
    if (shown == o.original_count) continue;
    const char* unit = unit_of(o.kind);
    std::string how = o.kind == ObjectKind::kMesh
                          ? "merged by vertex clustering, limit " + std::to_string(limits_.max_triangles) +
                                " triangles per page"
                          : "every " + std::to_string((o.original_count + shown - 1) / std::max<std::size_t>(shown, 1)) +
                                "th, limit " + std::to_string(limit_of(limits_, o.kind)) + " " + unit + " per page";
    notes.push_back(o.name + ": " + std::to_string(o.original_count) + " " + unit + ", " + std::to_string(shown) +
                    " shown (" + how + ")");
  }
  return notes;
}

SceneObject thin_by_stride(const SceneObject& object, std::size_t max_items) {
  const std::size_t n = object.positions.size();
  if (n <= max_items || max_items == 0) return object;
  if (object.pieces) {  // every k-th segment, kept whole
    const std::size_t k = (n + max_items - 1) / max_items;
    SceneObject out = object;
    out.positions.clear();
    out.colours.clear();
    out.values.clear();
    for (std::size_t i = 0; i + 1 < n; i += 2 * k) {
      for (std::size_t j = i; j < i + 2; ++j) {
        out.positions.push_back(object.positions[j]);
        if (!object.colours.empty()) out.colours.push_back(object.colours[j]);
        if (!object.values.empty()) out.values.push_back(object.values[j]);
      }
    }
    return out;
  }
  const std::size_t k = (n + max_items - 1) / max_items;
  SceneObject out = object;
  out.positions.clear();
  out.colours.clear();
  out.directions.clear();
  out.values.clear();
  for (std::size_t i = 0; i < n; i += k) {
    out.positions.push_back(object.positions[i]);
    if (!object.colours.empty()) out.colours.push_back(object.colours[i]);
    if (!object.values.empty()) out.values.push_back(object.values[i]);
    if (!object.directions.empty()) out.directions.push_back(object.directions[i]);
  }
  return out;
}

SceneObject thin_mesh(const SceneObject& mesh, std::size_t max_triangles) {
  if (mesh.triangles.size() <= max_triangles || max_triangles == 0 || mesh.positions.empty()) return mesh;
  Eigen::Vector3d lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Eigen::Vector3d& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Start where a uniform mesh of the box's area would have about max_triangles triangles.
  const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-9);
  const double area = extent.x() * extent.y() + extent.y() * extent.z() + extent.z() * extent.x();
  double cell = std::sqrt(2.0 * area / static_cast<double>(max_triangles));
  for (int round = 0; round < 200; ++round, cell *= 1.25) {
    std::unordered_map<std::uint64_t, std::uint32_t> first_in_cell;  // cell key -> new vertex index
    std::vector<std::uint32_t> remap(mesh.positions.size());
    SceneObject out = mesh;
    out.positions.clear();
    out.colours.clear();
    out.values.clear();
    out.triangles.clear();
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Eigen::Vector3d c = ((mesh.positions[i] - lo) / cell).array().floor();
      const std::uint64_t key =
          !c.allFinite() ? ~std::uint64_t{0}
                         : (static_cast<std::uint64_t>(c.x()) << 42) ^ (static_cast<std::uint64_t>(c.y()) << 21) ^
                               static_cast<std::uint64_t>(c.z());
      const auto [it, inserted] = first_in_cell.emplace(key, static_cast<std::uint32_t>(out.positions.size()));
      if (inserted) {
        out.positions.push_back(mesh.positions[i]);
        if (!mesh.colours.empty()) out.colours.push_back(mesh.colours[i]);
        if (!mesh.values.empty()) out.values.push_back(mesh.values[i]);
      }
      remap[i] = it->second;
    }
    for (const auto& t : mesh.triangles) {
      const std::array<std::uint32_t, 3> r = {remap[t[0]], remap[t[1]], remap[t[2]]};
      if (r[0] != r[1] && r[1] != r[2] && r[2] != r[0]) out.triangles.push_back(r);
    }
    if (out.triangles.size() <= max_triangles) return out;
  }
  SceneObject out = mesh;  // not reached for finite input: a single cell leaves no triangle
  out.triangles.clear();
  return out;
}

}  // namespace conform::html
