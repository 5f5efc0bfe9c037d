#include "conform/toolpath/intersection/intersection_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <utility>

#include "conform/core/constants.h"

namespace conform {
namespace {

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
  const bool paper = condition.size() == 2 && condition[0] == '1';
  check.message = (paper ? "(" + condition + ") " : "[" + condition + "] ") + what + text;
  return check;
}

namespace {

// Component label of every vertex (the smallest vertex index in it).
std::vector<std::int32_t> component_labels(const IntersectionGraph& graph) {
  std::vector<std::int32_t> parent(graph.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::int32_t v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (const auto& e : graph.edges) {
    const std::int32_t a = find(e[0]);
    const std::int32_t b = find(e[1]);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<std::int32_t> label(graph.vertices.size());
  for (std::size_t v = 0; v < label.size(); ++v) label[v] = find(static_cast<std::int32_t>(v));
  return label;
}

// [intersect], (1d), (1i), (1a): the local conditions.
CurveCheck check_local(const IntersectionGraph& graph) {
  if (graph.vertices.empty()) {
    CurveCheck check = curve_failure("intersect", "the meshes do not intersect", Eigen::Vector3d::Zero());
    check.message = "[intersect] the meshes do not intersect: no triangle of the leg crosses a triangle of the stub";
    return check;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> sorted;
  for (const auto& e : graph.edges) {
    if (e[0] == e[1]) {
      return curve_failure("1d", "a degenerate edge (both ends one vertex)", graph.vertices[std::size_t(e[0])]);
    }
    sorted.emplace_back(std::min(e[0], e[1]), std::max(e[0], e[1]));
  }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i] == sorted[i - 1]) {
      return curve_failure("1i", "two edges join the same two vertices", graph.vertices[std::size_t(sorted[i].first)]);
    }
  }
  const auto neighbours = adjacency(graph);
  for (std::size_t v = 0; v < neighbours.size(); ++v) {
    if (neighbours[v].size() < 2) {
      return curve_failure("1a", "the intersection is not a closed curve: an open end (a mesh border or hole crosses it)",
                           graph.vertices[v]);
    }
  }
  for (std::size_t v = 0; v < neighbours.size(); ++v) {
    if (neighbours[v].size() > 2) {
      return curve_failure("1a", "the intersection is not a simple closed curve: it branches, " +
                                     std::to_string(neighbours[v].size()) + " edges meet",
                           graph.vertices[v]);
    }
  }
  return {};
}

}  // namespace

int count_components(const IntersectionGraph& graph) {
  const std::vector<std::int32_t> label = component_labels(graph);
  int components = 0;
  for (std::size_t v = 0; v < label.size(); ++v) components += label[v] == static_cast<std::int32_t>(v) ? 1 : 0;
  return components;
}

CurveCheck check_intersection_graph(const IntersectionGraph& graph) {
  const MainCurve main = select_main_curve(graph, 0.0);
  return main.check;
}

MainCurve select_main_curve(const IntersectionGraph& graph, double max_island_ratio) {
  MainCurve main;
  main.check = check_local(graph);
  if (!main.check.ok) return main;
  const std::vector<std::int32_t> label = component_labels(graph);
  std::vector<double> length(graph.vertices.size(), 0.0);
  for (const auto& e : graph.edges) {
    length[static_cast<std::size_t>(label[static_cast<std::size_t>(e[0])])] +=
        (graph.vertices[static_cast<std::size_t>(e[0])] - graph.vertices[static_cast<std::size_t>(e[1])]).norm();
  }
  std::vector<std::int32_t> roots;
  for (std::size_t v = 0; v < label.size(); ++v) {
    if (label[v] == static_cast<std::int32_t>(v)) roots.push_back(static_cast<std::int32_t>(v));
  }
  // Longest first; ties by the smallest vertex index (deterministic).
  std::stable_sort(roots.begin(), roots.end(), [&](std::int32_t a, std::int32_t b) {
    return length[static_cast<std::size_t>(a)] > length[static_cast<std::size_t>(b)];
  });
  const std::int32_t keep = roots.front();
  main.main_length_mm = length[static_cast<std::size_t>(keep)];
  if (roots.size() > 1) {
    const double second = length[static_cast<std::size_t>(roots[1])];
    if (second >= max_island_ratio * main.main_length_mm) {
      std::ostringstream what;
      what << roots.size() << " separate intersection curves, not one (the longest " << main.main_length_mm
           << " mm, the next " << second << " mm); another one";
      main.check = curve_failure("one-curve", what.str(), graph.vertices[static_cast<std::size_t>(roots[1])]);
      return main;
    }
    main.islands = roots.size() - 1;
    main.longest_island_mm = second;
  }
  std::vector<std::int32_t> renumber(graph.vertices.size(), -1);
  for (std::size_t v = 0; v < graph.vertices.size(); ++v) {
    if (label[v] != keep) {
      ++main.island_vertices;
      continue;
    }
    renumber[v] = static_cast<std::int32_t>(main.graph.vertices.size());
    main.graph.vertices.push_back(graph.vertices[v]);
    main.graph.crossings.push_back(graph.crossings[v]);
  }
  for (const auto& e : graph.edges) {
    const std::int32_t a = renumber[static_cast<std::size_t>(e[0])];
    if (a >= 0) main.graph.edges.push_back({a, renumber[static_cast<std::size_t>(e[1])]});
  }
  return main;
}

}  // namespace conform
