#include "conform/toolpath/intersection/surface_intersection.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <unordered_map>

#include <Eigen/Dense>

#include "conform/core/error.h"

namespace conform {
namespace {

struct Piece {
  BezierPatch patch;  // in the working frame
  Eigen::AlignedBox3d box;
  double u0, u1, v0, v1;  // its parameter rectangle on its network
};

Piece make_piece(const BezierPatch& patch, double u0, double u1, double v0, double v1) {
  return {patch, patch.bounds(), u0, u1, v0, v1};
}

std::array<Piece, 4> split(const Piece& p) {
  const std::array<BezierPatch, 4> q = p.patch.subdivide(0.5, 0.5);
  const double um = 0.5 * (p.u0 + p.u1), vm = 0.5 * (p.v0 + p.v1);
  return {make_piece(q[0], p.u0, um, p.v0, vm), make_piece(q[1], um, p.u1, p.v0, vm),
          make_piece(q[2], p.u0, um, vm, p.v1), make_piece(q[3], um, p.u1, vm, p.v1)};
}

struct Search {
  const IntersectionOptions& options;
  std::vector<IntersectionPoint> leaves;
  bool overflow = false;
  std::size_t box_pairs = 0;
  bool work_overflow = false;

  void recurse(const Piece& a, const Piece& b, int depth) {
    if (overflow || work_overflow || !a.box.intersects(b.box)) return;
    if (++box_pairs > options.max_box_pairs) {  // bounded work whatever the input (a spike of 65 m, say)
      work_overflow = true;
      return;
    }
    const bool a_small = a.box.diagonal().norm() <= options.tolerance_mm || depth >= options.max_depth;
    const bool b_small = b.box.diagonal().norm() <= options.tolerance_mm || depth >= options.max_depth;
    if (a_small && b_small) {
      if (leaves.size() >= options.max_leaf_pairs) {
        overflow = true;
        return;
      }
      IntersectionPoint p;
      p.uv_a = {0.5 * (a.u0 + a.u1), 0.5 * (a.v0 + a.v1)};
      p.uv_b = {0.5 * (b.u0 + b.u1), 0.5 * (b.v0 + b.v1)};
      leaves.push_back(p);
      return;
    }
    if (a_small) {
      for (const Piece& q : split(b)) recurse(a, q, depth + 1);
    } else if (b_small) {
      for (const Piece& q : split(a)) recurse(q, b, depth + 1);
    } else {
      const std::array<Piece, 4> qa = split(a), qb = split(b);
      for (const Piece& x : qa) {
        for (const Piece& y : qb) recurse(x, y, depth + 1);
      }
    }
  }
};

// A bounding-volume tree over boxes (median split along the longest axis, leaves of up to 4): the patches of one
// network that a box of the other overlaps, in O(log n + hits) instead of a loop over all of them.
class BoxTree {
 public:
  explicit BoxTree(std::vector<Eigen::AlignedBox3d> boxes) : boxes_(std::move(boxes)) {
    order_.resize(boxes_.size());
    for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = static_cast<int>(k);
    nodes_.reserve(2 * boxes_.size() / 3 + 2);
    if (!boxes_.empty()) build(0, static_cast<int>(boxes_.size()));
  }
  // Calls visit(index) for every box overlapping `box`, in increasing index order within a leaf.
  template <class Visit>
  void query(const Eigen::AlignedBox3d& box, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<int> stack = {0};
    while (!stack.empty()) {
      const Node& node = nodes_[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (!node.box.intersects(box)) continue;
      if (node.left < 0) {
        for (int k = node.first; k < node.first + node.count; ++k) {
          const int index = order_[static_cast<std::size_t>(k)];
          if (boxes_[static_cast<std::size_t>(index)].intersects(box)) visit(index);
        }
      } else {
        stack.push_back(node.right);
        stack.push_back(node.left);
      }
    }
  }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1, first = 0, count = 0;
  };
  int build(int first, int count) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Eigen::AlignedBox3d box;
    for (int k = first; k < first + count; ++k) box.extend(boxes_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
    nodes_[static_cast<std::size_t>(id)].box = box;
    if (count <= 4) {
      nodes_[static_cast<std::size_t>(id)].first = first;
      nodes_[static_cast<std::size_t>(id)].count = count;
      return id;
    }
    Eigen::Index axis = 0;
    box.sizes().maxCoeff(&axis);
    const auto begin = order_.begin() + first, mid = begin + count / 2, end = begin + count;
    std::nth_element(begin, mid, end, [&](int x, int y) {
      const double cx = boxes_[static_cast<std::size_t>(x)].center()[axis], cy = boxes_[static_cast<std::size_t>(y)].center()[axis];
      return cx < cy || (cx == cy && x < y);
    });
    const int left = build(first, count / 2);
    const int right = build(first + count / 2, count - count / 2);
    nodes_[static_cast<std::size_t>(id)].left = left;
    nodes_[static_cast<std::size_t>(id)].right = right;
    return id;
  }
  std::vector<Eigen::AlignedBox3d> boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

// Points hashed by the integer cell of size `cell` they fall in: neighbours within a cell in O(1).
struct CellKey {
  long x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return static_cast<std::size_t>(k.x * 73856093L) ^ static_cast<std::size_t>(k.y * 19349663L) ^
           static_cast<std::size_t>(k.z * 83492791L);
  }
};
CellKey cell_of(const Eigen::Vector3d& p, double cell) {
  return {std::lround(std::floor(p.x() / cell)), std::lround(std::floor(p.y() / cell)), std::lround(std::floor(p.z() / cell))};
}
using CellMap = std::unordered_map<CellKey, std::vector<std::size_t>, CellHash>;

// Calls visit(k) for every hashed point in the 27 cells around p.
template <class Visit>
void around(const CellMap& map, const Eigen::Vector3d& p, double cell, Visit&& visit) {
  const CellKey c = cell_of(p, cell);
  for (long dx = -1; dx <= 1; ++dx) {
    for (long dy = -1; dy <= 1; ++dy) {
      for (long dz = -1; dz <= 1; ++dz) {
        const auto it = map.find({c.x + dx, c.y + dy, c.z + dz});
        if (it == map.end()) continue;
        for (std::size_t k : it->second) visit(k);
      }
    }
  }
}

// Rows: an orthonormal frame whose third axis is the patch's normal at its centre (identity if degenerate).
Eigen::Matrix3d local_frame(const BezierPatch& patch) {
  const Eigen::Vector3d n = patch.derivative(0.5, 0.5, 1, 0).cross(patch.derivative(0.5, 0.5, 0, 1));
  if (!(n.norm() > 0.0)) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d z = n.normalized();
  const Eigen::Vector3d x = (std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(z).normalized();
  Eigen::Matrix3d R;
  R.row(0) = x;
  R.row(1) = z.cross(x);
  R.row(2) = z;
  return R;
}

// Newton's method on A(ua, va) - B(ub, vb) = 0: three equations in four unknowns, the minimum-norm step
// J^T (J J^T)^-1 F moves to the nearest intersection point.
bool refine(const BezierNetwork& a, const BezierNetwork& b, IntersectionPoint* p) {
  Eigen::Vector4d x(p->uv_a.x(), p->uv_a.y(), p->uv_b.x(), p->uv_b.y());
  const ParameterDomain da = a.domain(), db = b.domain();
  for (int it = 0; it < 25; ++it) {
    const Eigen::Vector3d F = a.position(x[0], x[1]) - b.position(x[2], x[3]);
    if (F.norm() < 1e-11) break;
    Eigen::Matrix<double, 3, 4> J;
    J.col(0) = a.derivative(x[0], x[1], 1, 0);
    J.col(1) = a.derivative(x[0], x[1], 0, 1);
    J.col(2) = -b.derivative(x[2], x[3], 1, 0);
    J.col(3) = -b.derivative(x[2], x[3], 0, 1);
    const Eigen::Matrix3d JJt = J * J.transpose();
    const Eigen::Vector4d step = -J.transpose() * JJt.ldlt().solve(F);
    if (!step.allFinite() || step.norm() > 0.5) return false;  // a jump of half a patch: not converging locally
    x += step;
  }
  if (!da.contains(x[0], x[1]) || !db.contains(x[2], x[3])) return false;
  if ((a.position(x[0], x[1]) - b.position(x[2], x[3])).norm() > 1e-8) return false;
  p->uv_a = {x[0], x[1]};
  p->uv_b = {x[2], x[3]};
  return true;
}

// Keeps one point per cell of size `cell` (the first in sorted order): sorting by quantised position first makes
// the result independent of the recursion order.
std::vector<IntersectionPoint> thin(std::vector<IntersectionPoint> points, double cell) {
  std::map<std::tuple<long, long, long>, IntersectionPoint> cells;
  for (const IntersectionPoint& p : points) {
    const auto key = std::make_tuple(std::lround(std::floor(p.position.x() / cell)),
                                     std::lround(std::floor(p.position.y() / cell)),
                                     std::lround(std::floor(p.position.z() / cell)));
    cells.emplace(key, p);
  }
  std::vector<IntersectionPoint> kept;
  CellMap hashed;
  for (const auto& entry : cells) {
    const IntersectionPoint& p = entry.second;  // a named reference: lambdas may not capture structured bindings
    bool near = false;
    around(hashed, p.position, cell, [&](std::size_t k) { near = near || (kept[k].position - p.position).norm() < cell; });
    if (near) continue;
    hashed[cell_of(p.position, cell)].push_back(kept.size());
    kept.push_back(p);
  }
  return kept;
}

std::vector<IntersectionCurve> chain(const std::vector<IntersectionPoint>& points, double link);

}  // namespace

bool IntersectionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(tolerance_mm > 0.0) || !std::isfinite(tolerance_mm)) return fail("intersection tolerance must be > 0 mm");
  if (max_depth < 1 || max_depth > 60) return fail("intersection max_depth must be in [1, 60]");
  if (!(link_factor >= 1.5)) return fail("intersection link_factor must be >= 1.5");
  if (max_leaf_pairs < 1) return fail("intersection max_leaf_pairs must be >= 1");
  if (max_box_pairs < 1) return fail("intersection max_box_pairs must be >= 1");
  return true;
}

double IntersectionCurve::length_mm() const {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i].position - points[i - 1].position).norm();
  if (closed && points.size() > 2) length += (points.front().position - points.back().position).norm();
  return length;
}

IntersectionResult intersect_surfaces(const BezierNetwork& a, const BezierNetwork& b,
                                      const IntersectionOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error(error);
  // Top-level pairs by world boxes; each overlapping pair is then recursed in a frame whose z is the normal of the
  // second patch at its centre, where a gently curved patch has a thin box.
  Search search{options, {}, false, 0, false};
  std::vector<Eigen::AlignedBox3d> boxes_b;
  boxes_b.reserve(static_cast<std::size_t>(b.patch_rows()) * static_cast<std::size_t>(b.patch_cols()));
  for (int rb = 0; rb < b.patch_rows(); ++rb) {
    for (int cb = 0; cb < b.patch_cols(); ++cb) boxes_b.push_back(b.patch(rb, cb).bounds());
  }
  const BoxTree tree(std::move(boxes_b));
  std::vector<int> hits;
  for (int ra = 0; ra < a.patch_rows() && !search.work_overflow; ++ra) {
    for (int ca = 0; ca < a.patch_cols(); ++ca) {
      const BezierPatch& pa = a.patch(ra, ca);
      hits.clear();
      tree.query(pa.bounds(), [&](int k) { hits.push_back(k); });
      std::sort(hits.begin(), hits.end());  // the same order as a loop over all pairs: deterministic output
      for (int k : hits) {
        const int rb = k / b.patch_cols(), cb = k % b.patch_cols();
        const BezierPatch& pb = b.patch(rb, cb);
        const Eigen::Matrix3d R = local_frame(pb);
        search.recurse(make_piece(pa.transformed(R, Eigen::Vector3d::Zero()), ca, ca + 1, ra, ra + 1),
                       make_piece(pb.transformed(R, Eigen::Vector3d::Zero()), cb, cb + 1, rb, rb + 1), 0);
      }
    }
  }
  IntersectionResult result;
  result.leaf_pairs = search.leaves.size();
  result.box_pairs = search.box_pairs;
  if (search.work_overflow) {
    result.work_limit_hit = true;
    result.termination = "more than " + std::to_string(options.max_box_pairs) +
                         " box pairs examined (limit max_box_pairs): an outlier or a surface folded on itself";
    return result;
  }
  if (search.overflow) {
    result.termination = "more than " + std::to_string(options.max_leaf_pairs) +
                         " leaf pairs: the surfaces nearly coincide; offset one of them (a depth threshold)";
    return result;
  }
  std::vector<IntersectionPoint> found;
  for (IntersectionPoint& p : search.leaves) {
    if (options.refine && !refine(a, b, &p)) {
      ++result.unrefined;  // a box overlap without a nearby intersection: dropped
      continue;
    }
    p.position = a.position(p.uv_a.x(), p.uv_a.y());
    found.push_back(p);
  }
  const std::vector<IntersectionPoint> points = thin(found, 0.5 * options.tolerance_mm);
  result.points = points.size();
  for (const IntersectionPoint& p : points) {
    result.max_gap_mm = std::max(result.max_gap_mm, (p.position - b.position(p.uv_b.x(), p.uv_b.y())).norm());
  }
  result.curves = chain(points, options.link_factor * options.tolerance_mm);
  result.ok = true;
  result.termination = result.curves.empty() ? "the surfaces do not intersect" : "intersected";
  return result;
}

namespace {

// Greedy nearest-neighbour chaining: grow from the first unused point forwards, then backwards from its start.
// Neighbours come from a hash of cells of size `link`: O(n) for the whole chaining.
std::vector<IntersectionCurve> chain(const std::vector<IntersectionPoint>& points, double link) {
  std::vector<bool> used(points.size(), false);
  CellMap hashed;
  for (std::size_t k = 0; k < points.size(); ++k) hashed[cell_of(points[k].position, link)].push_back(k);
  auto nearest = [&](const Eigen::Vector3d& from) {
    int best = -1;
    double best_d = link;
    around(hashed, from, link, [&](std::size_t k) {
      const double d = (points[k].position - from).norm();
      if (!used[k] && (d < best_d || (d == best_d && static_cast<int>(k) < best))) best = static_cast<int>(k), best_d = d;
    });
    return best;
  };
  std::vector<IntersectionCurve> curves;
  for (std::size_t start = 0; start < points.size(); ++start) {
    if (used[start]) continue;
    used[start] = true;
    std::vector<IntersectionPoint> forward = {points[start]}, backward;
    for (int k = nearest(forward.back().position); k >= 0; k = nearest(forward.back().position)) {
      used[static_cast<std::size_t>(k)] = true;
      forward.push_back(points[static_cast<std::size_t>(k)]);
    }
    for (int k = nearest(points[start].position); k >= 0;
         k = nearest(backward.empty() ? points[start].position : backward.back().position)) {
      used[static_cast<std::size_t>(k)] = true;
      backward.push_back(points[static_cast<std::size_t>(k)]);
    }
    IntersectionCurve curve;
    curve.points.assign(backward.rbegin(), backward.rend());
    curve.points.insert(curve.points.end(), forward.begin(), forward.end());
    if (curve.points.size() < 3) continue;  // a stray point, not a curve
    curve.closed = curve.points.size() > 3 && (curve.points.front().position - curve.points.back().position).norm() <= link;
    curves.push_back(std::move(curve));
  }
  std::stable_sort(curves.begin(), curves.end(), [](const IntersectionCurve& x, const IntersectionCurve& y) {
    if (x.closed != y.closed) return x.closed;
    return x.points.size() > y.points.size();
  });
  return curves;
}

}  // namespace

bool polygon_contains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  if (polygon.size() < 3) return false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<Eigen::Vector2d> parameter_polygon_a(const IntersectionCurve& curve) {
  std::vector<Eigen::Vector2d> polygon;
  for (const IntersectionPoint& p : curve.points) polygon.push_back(p.uv_a);
  return polygon;
}

}  // namespace conform
