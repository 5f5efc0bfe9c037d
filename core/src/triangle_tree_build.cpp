// Building the triangle BVH: split at the median triangle centroid along the longest axis of the centroids' box
// (ties ordered by face index, so the same mesh gives the same tree), down to leaves of at most kLeafSize triangles,
// whose vertices are copied in leaf order so that a leaf is read from contiguous memory.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "conform/core/error.h"
#include "triangle_tree.h"

namespace conform::detail {
namespace {

constexpr std::int32_t kLeafSize = 4;

// Outward rounding to float: one float step beyond the nearest float, so never inside the double box.
float round_down(double v) { return std::nextafter(static_cast<float>(v), -std::numeric_limits<float>::infinity()); }
float round_up(double v) { return std::nextafter(static_cast<float>(v), std::numeric_limits<float>::infinity()); }

struct Subtree {
  Eigen::Vector3d lo, hi;  // padded box of its triangles
  std::int32_t ref = 0;    // as TriangleTree::Node::ref
  std::int32_t count = 0;  // as TriangleTree::Node::count
};

class Builder {
 public:
  Builder(const Mesh& mesh, TriangleTree& tree) : mesh_(mesh), tree_(tree) {
    double largest = 0.0;
    for (const Eigen::Vector3d& v : mesh.vertices) largest = std::max(largest, v.cwiseAbs().maxCoeff());
    // Boxes padded by far more than the rounding of a computed closest point (a few ulps of the coordinates), so
    // that a box is never farther from a query than a closest point computed on one of its triangles.
    pad_ = 1e-12 * (1.0 + largest);
    const std::size_t n = mesh.faces.size();
    order_.resize(n);
    keys_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    centroids_.resize(n);
    for (std::size_t f = 0; f < n; ++f) centroids_[f] = (vertex(f, 0) + vertex(f, 1) + vertex(f, 2)) / 3.0;
  }

  void build() {
    tree_.nodes.reserve(order_.size() / static_cast<std::size_t>(kLeafSize) + 1);
    const Subtree root = subtree(0, static_cast<std::int32_t>(order_.size()), 1);
    tree_.root_lo = root.lo;
    tree_.root_hi = root.hi;
    tree_.root_count = root.count;
    tree_.triangles.reserve(order_.size());
    for (std::int32_t f : order_) {
      const auto i = static_cast<std::size_t>(f);
      tree_.triangles.push_back({vertex(i, 0), vertex(i, 1), vertex(i, 2), f});
    }
  }

 private:
  const Eigen::Vector3d& vertex(std::size_t f, int k) const {
    return mesh_.vertices[static_cast<std::size_t>(mesh_.faces[f][static_cast<std::size_t>(k)])];
  }

  // The subtree over order_[begin, end). Boxes are made bottom-up (a parent's is the union of its children's), so
  // only the centroids' box is computed on the way down.
  Subtree subtree(std::int32_t begin, std::int32_t end, int depth) {
    if (depth > kMaxTreeDepth) throw Error("triangle index: tree deeper than " + std::to_string(kMaxTreeDepth));
    Subtree s;
    if (end - begin <= kLeafSize) {
      s.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
      s.hi = -s.lo;
      for (std::int32_t i = begin; i < end; ++i) {
        const auto f = static_cast<std::size_t>(order_[static_cast<std::size_t>(i)]);
        for (int k = 0; k < 3; ++k) {
          s.lo = s.lo.cwiseMin(vertex(f, k));
          s.hi = s.hi.cwiseMax(vertex(f, k));
        }
      }
      s.lo.array() -= pad_;
      s.hi.array() += pad_;
      s.ref = begin;
      s.count = end - begin;
      return s;
    }
    Eigen::Vector3d clo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d chi = -clo;
    for (std::int32_t i = begin; i < end; ++i) {
      const Eigen::Vector3d& c = centroids_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
      clo = clo.cwiseMin(c);
      chi = chi.cwiseMax(c);
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const std::int32_t mid = begin + (end - begin) / 2;
    // The median on a contiguous copy of (coordinate, face): the same order as comparing through the centroids, at a
    // third of the cost (no scattered reads inside nth_element).
    const auto first = keys_.begin() + begin, last = keys_.begin() + end;
    for (std::int32_t i = begin; i < end; ++i) {
      const std::int32_t f = order_[static_cast<std::size_t>(i)];
      keys_[static_cast<std::size_t>(i)] = {centroids_[static_cast<std::size_t>(f)][axis], f};
    }
    std::nth_element(first, keys_.begin() + mid, last, [](const Key& x, const Key& y) {
      return x.value < y.value || (x.value == y.value && x.face < y.face);
    });
    for (std::int32_t i = begin; i < end; ++i) {
      order_[static_cast<std::size_t>(i)] = keys_[static_cast<std::size_t>(i)].face;
    }
    s.ref = static_cast<std::int32_t>(tree_.nodes.size());
    tree_.nodes.emplace_back();
    const Subtree children[2] = {subtree(begin, mid, depth + 1), subtree(mid, end, depth + 1)};
    s.lo = children[0].lo.cwiseMin(children[1].lo);
    s.hi = children[0].hi.cwiseMax(children[1].hi);
    TriangleTree::Node& node = tree_.nodes[static_cast<std::size_t>(s.ref)];
    for (int c = 0; c < 2; ++c) {
      for (int k = 0; k < 3; ++k) {
        node.lo[c][k] = round_down(children[c].lo[k]);
        node.hi[c][k] = round_up(children[c].hi[k]);
      }
      node.ref[c] = children[c].ref;
      node.count[c] = children[c].count;
    }
    return s;
  }

  const Mesh& mesh_;
  TriangleTree& tree_;
  double pad_ = 0.0;
  struct Key {
    double value;
    std::int32_t face;
  };
  std::vector<std::int32_t> order_;
  std::vector<Key> keys_;  // scratch for the median split
  std::vector<Eigen::Vector3d> centroids_;
};

}  // namespace

void build_tree(const Mesh& mesh, TriangleTree& tree) { Builder(mesh, tree).build(); }

}  // namespace conform::detail
