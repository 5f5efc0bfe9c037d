#include "conform/toolpath/intersection_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <utility>

namespace conform {
namespace {

constexpr double kPi = 3.141592653589793;

std::vector<std::vector<std::int32_t>> adjacency(const IntersectionGraph& graph) {
  std::vector<std::vector<std::int32_t>> neighbours(graph.vertices.size());
  for (const auto& e : graph.edges) {
    neighbours[static_cast<std::size_t>(e[0])].push_back(e[1]);
    neighbours[static_cast<std::size_t>(e[1])].push_back(e[0]);
  }
  return neighbours;
}

}  // namespace

IntersectionGraph weld_segments(const std::vector<IntersectionSegment>& segments) {
  std::vector<EdgeCrossing> all;
  all.reserve(2 * segments.size());
  for (const IntersectionSegment& s : segments) {
    all.push_back(s.ends[0]);
    all.push_back(s.ends[1]);
  }
  std::sort(all.begin(), all.end(), [](const EdgeCrossing& x, const EdgeCrossing& y) { return x.key_less(y); });
  IntersectionGraph graph;
  for (const EdgeCrossing& c : all) {
    if (graph.crossings.empty() || !graph.crossings.back().same_key(c)) {
      graph.crossings.push_back(c);
      graph.vertices.push_back(c.point);
    }
  }
  const auto index_of = [&](const EdgeCrossing& c) {
    const auto it = std::lower_bound(graph.crossings.begin(), graph.crossings.end(), c,
                                     [](const EdgeCrossing& x, const EdgeCrossing& y) { return x.key_less(y); });
    return static_cast<std::int32_t>(it - graph.crossings.begin());
  };
  graph.edges.reserve(segments.size());
  for (const IntersectionSegment& s : segments) graph.edges.push_back({index_of(s.ends[0]), index_of(s.ends[1])});
  return graph;
}

CurveCheck curve_failure(const std::string& condition, const std::string& what, const Eigen::Vector3d& where) {
  CurveCheck check;
  check.ok = false;
  check.condition = condition;
  check.where = where;
  double azimuth = std::atan2(where.y(), where.x());
  if (azimuth < 0.0) azimuth += 2.0 * kPi;
  check.azimuth_rad = azimuth;
  char text[160];
  std::snprintf(text, sizeof text, " at azimuth %.2f deg, (%.3f, %.3f, %.3f) mm", azimuth * 180.0 / kPi, where.x(),
                where.y(), where.z());
  check.message = "(" + condition + ") " + what + text;
  return check;
}

int count_components(const IntersectionGraph& graph) {
  std::vector<std::int32_t> parent(graph.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::int32_t v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  int components = static_cast<int>(graph.vertices.size());
  for (const auto& e : graph.edges) {
    const std::int32_t a = find(e[0]);
    const std::int32_t b = find(e[1]);
    if (a == b) continue;
    parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    --components;
  }
  return components;
}

CurveCheck check_intersection_graph(const IntersectionGraph& graph) {
  if (graph.vertices.empty()) {
    CurveCheck check = curve_failure("1a", "the meshes do not intersect", Eigen::Vector3d::Zero());
    check.message = "(1a) the meshes do not intersect: no triangle of the leg crosses a triangle of the stub";
    return check;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> sorted;
  for (const auto& e : graph.edges) {
    if (e[0] == e[1]) {
      return curve_failure("1b", "a degenerate edge (both ends one vertex)", graph.vertices[std::size_t(e[0])]);
    }
    sorted.emplace_back(std::min(e[0], e[1]), std::max(e[0], e[1]));
  }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i] == sorted[i - 1]) {
      return curve_failure("1c", "two edges join the same two vertices", graph.vertices[std::size_t(sorted[i].first)]);
    }
  }
  const auto neighbours = adjacency(graph);
  for (std::size_t v = 0; v < neighbours.size(); ++v) {
    if (neighbours[v].size() < 2) {
      return curve_failure("1d", "the intersection is not closed: an open end (a mesh border or hole crosses it)",
                           graph.vertices[v]);
    }
  }
  for (std::size_t v = 0; v < neighbours.size(); ++v) {
    if (neighbours[v].size() > 2) {
      return curve_failure("1e", "the intersection branches: " + std::to_string(neighbours[v].size()) + " edges meet",
                           graph.vertices[v]);
    }
  }
  const int components = count_components(graph);
  if (components != 1) {
    // Name a point of the second curve: the first vertex not connected to vertex 0.
    std::vector<char> seen(graph.vertices.size(), 0);
    std::vector<std::int32_t> stack{0};
    seen[0] = 1;
    while (!stack.empty()) {
      const std::int32_t v = stack.back();
      stack.pop_back();
      for (const std::int32_t w : neighbours[static_cast<std::size_t>(v)]) {
        if (!seen[static_cast<std::size_t>(w)]) {
          seen[static_cast<std::size_t>(w)] = 1;
          stack.push_back(w);
        }
      }
    }
    const auto other = static_cast<std::size_t>(std::find(seen.begin(), seen.end(), 0) - seen.begin());
    return curve_failure("1f", std::to_string(components) + " separate intersection curves, not one; another one",
                         graph.vertices[other]);
  }
  return {};
}

}  // namespace conform
