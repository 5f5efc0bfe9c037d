#pragma once
// The boundary of a triangle mesh: its edges used by exactly one triangle, ordered into polylines. A surface with a
// hole (a porthole in a plate, a cockpit opening in a barrel) has one closed loop per hole plus its outer rim; a strip
// whose boundary ends at a non-manifold vertex gives open chains. Used by `conform sicp` to take the nominal contour
// from a CAD surface.

#include <vector>

#include "conform/core/mesh.h"
#include "conform/core/polyline.h"

namespace conform {

// Every boundary of `mesh` as a polyline, in the direction its triangles wind (the surface lies to the left when seen
// from the side the normals point to). Closed loops have closed = true and do not repeat their first point. Where
// more than two boundary edges meet at a vertex (two holes touching at a corner), chains are cut there and returned
// open. Order: by the lowest vertex index each polyline starts from, so the same mesh gives the same answer.
// Throws conform::Error for a face index out of range or a non-finite vertex.
std::vector<Polyline> boundary_polylines(const Mesh& mesh);

// The boundary vertex indices behind boundary_polylines, one list per polyline (same order).
std::vector<std::vector<int>> boundary_loops(const Mesh& mesh);

}  // namespace conform
