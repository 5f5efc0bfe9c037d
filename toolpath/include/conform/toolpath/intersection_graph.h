#pragma once
// The intersection segments welded into a graph (vertices = edge crossings, named by (mesh edge, crossed triangle),
// so welding is exact), and the graph checked against the conditions of Lind & Ystgaard (2020), Sec. 3, for a curve
// the tool can follow. Our numbering of those conditions (the failures name it):
//
//   (1a) the meshes intersect: the graph has vertices            (1b) no edge is degenerate (both ends one vertex)
//   (1c) no two edges join the same two vertices                 (1d) no vertex of degree 1 (the curve is closed)
//   (1e) no vertex of degree > 2 (the curve does not branch)     (1f) the graph is connected: one single closed curve
//   (1g) no vertex on the stub axis (its azimuth is defined)     (1h) the azimuth increases monotonically along it
//   (1i) it winds exactly once around the stub axis: its projection on the stub's x-y plane is a simple (Jordan)
//        curve around the axis.
// (1a)-(1f) are checked here, (1g)-(1i) by order_by_azimuth (azimuth_path.h).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/mesh_intersection.h"

namespace conform {

struct IntersectionGraph {
  std::vector<Eigen::Vector3d> vertices;           // mm, in the frame of the meshes
  std::vector<EdgeCrossing> crossings;             // the name of each vertex (same order)
  std::vector<std::array<std::int32_t, 2>> edges;  // one per segment, in segment order
};

// A check that failed: which condition, a message naming it and where (azimuth about the stub axis, coordinates).
struct CurveCheck {
  bool ok = true;
  std::string condition;  // "1a" ... "1i"; empty when ok
  std::string message;    // e.g. "(1e) the intersection branches: 4 edges meet at azimuth 93.2 deg, (x, y, z) mm"
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  double azimuth_rad = 0.0;
};

// Vertices in the order of their names (deterministic).
IntersectionGraph weld_segments(const std::vector<IntersectionSegment>& segments);

// Conditions (1a)-(1f); the first that fails. Azimuths are about the z axis of the meshes' frame (the stub axis).
CurveCheck check_intersection_graph(const IntersectionGraph& graph);

// The failure for a condition at a point: the message "(<condition>) <what> at azimuth A deg, (x, y, z) mm".
CurveCheck curve_failure(const std::string& condition, const std::string& what, const Eigen::Vector3d& where);

// The number of connected components (closed curves when every degree is 2).
int count_components(const IntersectionGraph& graph);

}  // namespace conform
