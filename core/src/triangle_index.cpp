// Closest-point queries on the triangle BVH (built in triangle_tree_build.cpp): an explicit stack, the nearer child
// first, leaves tested as soon as they are reached, and every box skipped that is farther than the best triangle so
// far. The answer is the minimum of (squared distance, face index) over all faces, exactly what a brute-force loop
// over closest_point_on_triangle gives, whatever the tree's shape.

#include "conform/core/triangle_index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "triangle_tree.h"

namespace conform {

// The pseudo-normals only give signs (normal_at): built on first use from the mesh kept here, so that point-to-surface
// ICP, which measures along its own smooth normals, does not pay for them (a third of the index's build time).
struct TriangleIndex::Impl : detail::TriangleTree {
  Mesh source;
  std::once_flag normals_once;
};

namespace {

using detail::TriangleTree;

// A box is skipped only when it is farther than the best triangle by more than rounding could explain; together
// with the boxes' padding this keeps the tree's answer identical to a brute-force loop.
constexpr double kPruneSlack = 1e-12;

bool pruned(double box_d2, double best_d2) { return box_d2 > best_d2 * (1.0 + kPruneSlack); }

double box_sq_distance(const float* lo, const float* hi, const Eigen::Vector3d& p) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({static_cast<double>(lo[k]) - p[k], p[k] - static_cast<double>(hi[k]), 0.0});
    d2 += d * d;
  }
  return d2;
}

double box_sq_distance(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& p) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

// Keeps the smallest (squared distance, face) seen.
void test_leaf(const TriangleTree& tree, std::int32_t first, std::int32_t count, const Eigen::Vector3d& query,
               SurfacePoint& best) {
  for (std::int32_t i = first; i < first + count; ++i) {
    const TriangleTree::Triangle& t = tree.triangles[static_cast<std::size_t>(i)];
    const SurfacePoint s = closest_point_on_triangle(query, t.a, t.b, t.c);
    if (s.sq_distance < best.sq_distance ||
        (s.sq_distance == best.sq_distance && (best.face < 0 || t.face < best.face))) {
      best = s;
      best.face = t.face;
    }
  }
}

void check_mesh(const Mesh& mesh) {
  if (!mesh.has_faces()) throw Error("triangle index: the mesh has no faces (a point cloud cannot be indexed)");
  if (mesh.faces.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 3)) {
    throw Error("triangle index: " + std::to_string(mesh.faces.size()) + " faces are more than it can hold");
  }
  check_consistent(mesh, "triangle index");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw Error("triangle index: vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
}

}  // namespace

TriangleIndex::TriangleIndex(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  check_mesh(mesh);
  impl_->source = mesh;
  impl_->faces = mesh.faces;
  detail::build_tree(mesh, *impl_);
}

TriangleIndex::~TriangleIndex() = default;
TriangleIndex::TriangleIndex(TriangleIndex&&) noexcept = default;
TriangleIndex& TriangleIndex::operator=(TriangleIndex&&) noexcept = default;

std::size_t TriangleIndex::face_count() const { return impl_->faces.size(); }

SurfacePoint TriangleIndex::closest(const Eigen::Vector3d& query, double max_distance) const {
  if (!query.allFinite()) throw Error("triangle index: the query point has a NaN or infinite coordinate");
  if (!(max_distance >= 0.0)) throw Error("triangle index: the search distance must be >= 0 (or infinite)");
  const TriangleTree& tree = *impl_;
  SurfacePoint best;
  best.sq_distance = max_distance * max_distance;
  const double root_d2 = box_sq_distance(tree.root_lo, tree.root_hi, query);
  if (pruned(root_d2, best.sq_distance)) return best;
  if (tree.root_count > 0) {
    test_leaf(tree, 0, tree.root_count, query, best);
    return best;
  }
  struct Entry {
    std::int32_t node;
    double d2;
  };
  std::array<Entry, detail::kMaxTreeDepth + 2> stack;
  int top = 0;
  stack[top++] = {0, root_d2};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (pruned(entry.d2, best.sq_distance)) continue;
    const TriangleTree::Node& n = tree.nodes[static_cast<std::size_t>(entry.node)];
    const double d2[2] = {box_sq_distance(n.lo[0], n.hi[0], query), box_sq_distance(n.lo[1], n.hi[1], query)};
    const int near = d2[1] < d2[0] ? 1 : 0;
    const int order[2] = {near, 1 - near};
    // Leaves now, nearer first: their triangles tighten the bound before any inner box is judged.
    for (int c : order) {
      if (n.count[c] > 0 && !pruned(d2[c], best.sq_distance)) test_leaf(tree, n.ref[c], n.count[c], query, best);
    }
    // Inner children on the stack, the nearer on top.
    for (int c : {order[1], order[0]}) {
      if (n.count[c] == 0 && !pruned(d2[c], best.sq_distance)) stack[top++] = {n.ref[c], d2[c]};
    }
  }
  return best;
}

namespace {

// Appends the slots of the triangles within sqrt(r2) of `query` (by their double-precision closest points; a box is
// never closer than the triangles it holds); false as soon as there are more than max_slots.
bool collect_slots(const TriangleTree& tree, const Eigen::Vector3d& query, double r2, std::size_t max_slots,
                   std::vector<std::int32_t>& slots) {
  const auto leaf = [&](std::int32_t first, std::int32_t count) {
    for (std::int32_t i = first; i < first + count; ++i) {
      const TriangleTree::Triangle& t = tree.triangles[static_cast<std::size_t>(i)];
      if (closest_point_on_triangle(query, t.a, t.b, t.c).sq_distance > r2) continue;
      if (slots.size() == max_slots) return false;
      slots.push_back(i);
    }
    return true;
  };
  if (box_sq_distance(tree.root_lo, tree.root_hi, query) > r2) return true;
  if (tree.root_count > 0) return leaf(0, tree.root_count);
  std::array<std::int32_t, detail::kMaxTreeDepth + 2> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const TriangleTree::Node& n = tree.nodes[static_cast<std::size_t>(stack[--top])];
    for (int c = 0; c < 2; ++c) {
      if (box_sq_distance(n.lo[c], n.hi[c], query) > r2) continue;
      if (n.count[c] == 0) {
        stack[top++] = n.ref[c];
      } else if (!leaf(n.ref[c], n.count[c])) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

SurfacePoint TriangleIndex::closest_with_slots(const Eigen::Vector3d& query, double max_distance, double min_reach,
                                               std::size_t max_slots, std::vector<std::int32_t>& slots,
                                               double* reach) const {
  slots.clear();
  const SurfacePoint best = closest(query, max_distance);
  const double distance = std::sqrt(best.sq_distance);
  *reach = std::max(distance, min_reach);
  if (!best.found() || !std::isfinite(*reach)) return best;
  // Widened by far more than double rounding, so that no triangle the bound needs is left out.
  const double r = distance + 2.0 * *reach;
  if (!collect_slots(*impl_, query, r * r * (1.0 + 1e-9) + 1e-18, max_slots, slots)) slots.clear();
  return best;
}

SurfacePoint TriangleIndex::closest_among(const Eigen::Vector3d& query, const std::int32_t* slots, std::size_t count,
                                          double max_distance) const {
  if (!query.allFinite()) throw Error("triangle index: the query point has a NaN or infinite coordinate");
  if (!(max_distance >= 0.0)) throw Error("triangle index: the search distance must be >= 0 (or infinite)");
  SurfacePoint best;
  best.sq_distance = max_distance * max_distance;
  // One triangle at a time through test_leaf: the same (squared distance, face) order as closest().
  for (std::size_t k = 0; k < count; ++k) test_leaf(*impl_, slots[k], 1, query, best);
  return best;
}

Eigen::Vector3d TriangleIndex::normal_at(const SurfacePoint& point) const {
  if (!point.found()) return Eigen::Vector3d::Zero();
  const auto f = static_cast<std::size_t>(point.face);
  if (f >= impl_->faces.size()) {
    throw Error("triangle index: face " + std::to_string(point.face) + " is not one of its " +
                std::to_string(impl_->faces.size()) + " faces");
  }
  std::call_once(impl_->normals_once, [this] { detail::build_pseudo_normals(impl_->source, *impl_); });
  const auto offset = [&](TriangleFeature first) {
    return static_cast<std::size_t>(static_cast<int>(point.feature) - static_cast<int>(first));
  };
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  switch (point.feature) {
    case TriangleFeature::kFace:
      break;
    case TriangleFeature::kEdge01:
    case TriangleFeature::kEdge12:
    case TriangleFeature::kEdge20:
      normal = impl_->edge_normals[3 * f + offset(TriangleFeature::kEdge01)];
      break;
    case TriangleFeature::kVertex0:
    case TriangleFeature::kVertex1:
    case TriangleFeature::kVertex2:
      normal = impl_->vertex_normals[static_cast<std::size_t>(impl_->faces[f][offset(TriangleFeature::kVertex0)])];
      break;
  }
  // A pseudo-normal that cancels out (a sheet folded onto itself) or a face without area falls back to the face's
  // own normal, which is zero only when the face and all its neighbours have no area.
  return normal.squaredNorm() == 0.0 ? impl_->face_normals[f] : normal;
}

}  // namespace conform
