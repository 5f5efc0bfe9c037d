#pragma once
// The intersection segments welded into a graph (vertices = edge crossings, named by (mesh edge, crossed triangle),
// so welding is exact), and the graph checked against the conditions of Lind & Ystgaard (2020), Eq. (1a)-(1i), with
// the paper's numbering and meaning:
//
//   (1a) closed curve: every vertex has exactly two edges (degree 1: the curve is open, a mesh border or hole
//        crosses it; degree > 2: it branches)
//   (1b), (1e) closedness, (1c), (1f) coverage, (1g) reciprocity: hold by construction here (edges are index pairs
//        into the vertex list, the adjacency is built from the edges), so they are not checked
//   (1d) non-degeneracy: no edge joins a vertex to itself
//   (1h) uniqueness of vertices: no two vertices at the same coordinates (order_by_azimuth merges coincident
//        neighbours along the curve, a zero-length edge; two coincident vertices elsewhere fail: the curve touches
//        itself)
//   (1i) uniqueness of edges: no two edges join the same two vertices
//
// The project's own conditions (named, not numbered, so they are not mistaken for the paper's):
//   [intersect]  the meshes intersect at all
//   [one-curve]  one closed curve: further loops far shorter than the main one (noise islands where the surfaces
//                nearly touch) are dropped and reported; a second loop of similar size fails
//   [axis]       no vertex on the stub axis (its azimuth is defined)
//   [azimuth]    the azimuth increases along the curve, up to local backtracks within a tolerance (the paper's
//                requirement that the curve be parameterisable by azimuth, well-ordered in Algorithm 1)
//   [jordan]     the curve goes once round the stub axis: its projection on the stub's x-y plane is a Jordan curve
//                enclosing the axis (winding number 1)
// (1a), (1d), (1i), [intersect] and [one-curve] are checked here; (1h), [axis], [azimuth], [jordan] by
// order_by_azimuth (azimuth_path.h).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/intersection/mesh_intersection.h"

namespace conform {

struct IntersectionGraph {
  std::vector<Eigen::Vector3d> vertices;           // mm, in the frame of the meshes
  std::vector<EdgeCrossing> crossings;             // the name of each vertex (same order)
  std::vector<std::array<std::int32_t, 2>> edges;  // one per segment, in segment order
};

// A check that failed: which condition, a message naming it and where (azimuth about the stub axis, coordinates).
struct CurveCheck {
  bool ok = true;
  std::string condition;  // "1a", "1d", "1h", "1i", "intersect", "one-curve", "axis", "azimuth", "jordan"; empty when ok
  std::string message;    // e.g. "(1a) the intersection branches: 4 edges meet at azimuth 93.2 deg, (x, y, z) mm"
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  double azimuth_rad = 0.0;
};

// Vertices in the order of their names (deterministic).
IntersectionGraph weld_segments(const std::vector<IntersectionSegment>& segments);

// [intersect], (1d), (1i), (1a) and [one-curve] (no island dropping: any second curve fails); the first that fails.
// Azimuths are about the z axis of the meshes' frame (the stub axis).
CurveCheck check_intersection_graph(const IntersectionGraph& graph);

// Islands: closed loops of the graph other than the longest one.
struct MainCurve {
  CurveCheck check;                 // [intersect], (1d), (1i), (1a), or [one-curve] when a second loop is too long
  IntersectionGraph graph;          // the longest loop only (vertices renumbered, their order kept)
  std::size_t islands = 0;          // loops dropped
  std::size_t island_vertices = 0;  // their vertices
  double longest_island_mm = 0.0;   // the longest dropped loop's length
  double main_length_mm = 0.0;      // the kept loop's length
};

// As check_intersection_graph, but loops shorter than max_island_ratio x the longest loop are dropped (reported);
// a loop at least that long fails [one-curve]. max_island_ratio in [0, 1); 0 drops nothing.
MainCurve select_main_curve(const IntersectionGraph& graph, double max_island_ratio);

// The failure for a condition at a point: the message "(<condition>) <what> at azimuth A deg, (x, y, z) mm" for the
// paper's conditions, "[<condition>] ..." for the project's.
CurveCheck curve_failure(const std::string& condition, const std::string& what, const Eigen::Vector3d& where);

// The number of connected components (closed curves when every degree is 2).
int count_components(const IntersectionGraph& graph);

}  // namespace conform
