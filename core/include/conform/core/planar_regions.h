#pragma once
// Which triangles of a mesh lie on a plane of the part, as opposed to a chord of a curved surface. The smooth surface
// model (core/phong_surface.h) must leave a plane flat: a flat CAD face meeting a tangent fillet shares vertices with
// the fillet's first chord, whose face normal is tilted by half the chord angle, so averaged vertex normals tilt the
// flat face's corners and Phong tessellation bulges it (0.27 mm out of a 40 mm face next to an R10 fillet). Across a
// tangent (G1) junction the surface normal is the plane's, so the plane's faces keep their own normal and the curved
// faces take the plane's normal at the vertices they share with it.
//
//   const std::vector<unsigned char> flat = planar_faces(mesh);   // 1 per face on a plane
//
// A region is a maximal set of edge-connected faces whose vertices lie within a float-rounding tolerance of the plane
// of its largest face. Coplanar faces alone do not make a plane: a tessellated cylinder's strips are pairs of coplanar
// triangles. A region is a plane when
//  - a vertex has its whole fan inside it (a curved surface has no flat vertex fan: every vertex of a cylinder's
//    tessellation joins two strips), or
//  - it is at least kPlaneWidthRatio times as wide as every region it meets across an edge that is not a crease: a
//    tessellation at a chordal deflection d gives chords of width sqrt(8 d R) on a radius R, so a chord twice as
//    wide as its neighbours would have four times their sagitta; it is no chord of the same curved surface. (A 10 mm
//    side between R10 fillets exported in 4 chords of 3.9 mm is 2.6 times as wide.)
// Scanner meshes (noise: no two faces coplanar) keep single-face regions of similar widths and stay smooth.

#include <vector>

#include "conform/core/mesh.h"

namespace conform {

constexpr double kPlaneWidthRatio = 2.0;

// Per face: 1 on a plane (see above), 0 otherwise and for a face without area. crease_angle_rad: faces meeting at more
// than this are not neighbours for the width test (a box's faces are planes however narrow the next one is).
// Throws conform::Error for a face index out of range.
std::vector<unsigned char> planar_faces(const Mesh& mesh, double crease_angle_rad);

}  // namespace conform
