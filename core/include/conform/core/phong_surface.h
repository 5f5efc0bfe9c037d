#pragma once
// The smooth surface a triangle mesh's vertices and normals describe, for measuring distances without the flat
// facets' chord error: Phong tessellation (Boubekeur & Alexa 2008) of the closest point on the flat triangles. Used by
// point-to-surface ICP (registration/) and by the signed deviation (evaluation/), so both see the same surface.
//
//   const TriangleIndex index(mesh);
//   const PhongSurface smooth(mesh);                         // normals per face corner, creases kept sharp
//   const PhongPoint p = smooth.lift(index.closest(q));      // p.point on the smooth surface, p.normal there
//
// Flat facets of a curved surface lie inside it by up to the chord error (kappa h^2 / 8 at an edge's middle; a CAD
// tessellation's deflection), on average about a third of it: a systematic offset of every deviation and a bias of
// every pose. Phong tessellation with shape factor 1/2 reproduces a quadratic surface exactly from its vertices and
// their normals. Across a crease (faces meeting at more than the crease angle: a CAD edge, a box's corner) each side
// keeps its own normal, so flat faces stay flat and sharp edges stay sharp.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/core/triangle_index.h"

namespace conform {

// 30 deg, chosen on align's seed sweeps (docs/align.md): 20 also took the ribbed plate's steep rib ends (under-sampled
// by its mesh) for creases, 40 rounded the box part's 45 deg chamfer; a 4 mm mesh of a 150 mm radius (1.5 deg between
// neighbouring faces) is smooth.
constexpr double kDefaultCreaseAngleRad = 30.0 * 3.14159265358979323846 / 180.0;

struct PhongPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // on the smooth surface, mm
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit; zero for a face without area
  // False when the face is flat there (every corner normal is the face's own, or the face has no area): point is
  // then the flat closest point itself.
  bool lifted = false;
};

// Per vertex: 1 when every face around it is within the crease angle of its normal and of each other (the surface is
// smooth there), 0 at a crease or a corner (a 45 deg chamfer's edge too) and for a vertex without faces. normals: one
// unit normal per vertex.
std::vector<unsigned char> smooth_vertices(const Mesh& mesh, const std::vector<Eigen::Vector3d>& normals,
                                           double crease_angle_rad = kDefaultCreaseAngleRad);

class PhongSurface {
 public:
  // vertex_normals: one unit normal per vertex (e.g. a mesh's own), or empty: angle-weighted normals of the faces
  // around each vertex (Thuermer & Wuethrich 1998; unlike area weights they do not lean towards the side a
  // triangulation happens to split more often). At a vertex that is not smooth (smooth_vertices), each face's corner
  // gets the angle-weighted normal of the faces around the vertex within the crease angle of its own: the curved side
  // of a cylinder's rim is curved up to the rim, the flat cap stays flat. Keeps its own copy of the mesh. Throws
  // conform::Error for a face index out of range or a vertex_normals of the wrong size. with_rims false: the rims
  // nearest() needs are not found (ICP lifts its pairs only: finding them sorts every edge, 0.15 s of an align
  // against a 100k-face mesh), and nearest() throws.
  explicit PhongSurface(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normals = {},
                        double crease_angle_rad = kDefaultCreaseAngleRad, bool with_rims = true);

  // The closest point s on the flat triangles (TriangleIndex::closest over the same mesh, s.found()) moved onto the
  // smooth surface, Eq. (2)-(3) of Boubekeur & Alexa with shape factor 1/2, and the interpolated normal there.
  PhongPoint lift(const SurfacePoint& s) const;

  // The point of the smooth surface nearest q, for a signed distance, given s = index.closest(q) (found): lift(s),
  // except beside a rim, a crease where a face kept flat along it (a cylinder's cap) meets a curved one (its side).
  // The curved face's edge there is lifted off the chord by up to the chord's sagitta, in the flat face's plane, so
  // the plane reaches to that curve and not to the chord: where the curve bulges out of the flat face (a convex rim),
  // a q over the sliver between chord and curve is measured to the plane (lift(s) would put it on the curved side
  // and sign it by the side's normal: 0.1 mm under a cap read -0.1); where the curve cuts into the flat face (a
  // hole's rim), a q over the part of the face beyond the curve is measured to the curved face. lifted is false when
  // none of this moves the point and s lies on a flat face: measure to s itself.
  PhongPoint nearest(const Eigen::Vector3d& q, const SurfacePoint& s) const;

  const std::vector<unsigned char>& smooth() const { return smooth_; }
  // The normal face f uses at its k-th corner (unit, or zero where the faces around it have no area).
  const Eigen::Vector3d& corner_normal(std::size_t f, int k) const {
    return normals_[static_cast<std::size_t>(corners_[f][static_cast<std::size_t>(k)])];
  }

 private:
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Face> faces_;
  std::vector<Eigen::Vector3d> normals_;              // the vertex normals, then the corners' own at creases
  std::vector<std::array<std::int32_t, 3>> corners_;  // per face: its corners' indices into normals_
  std::vector<unsigned char> smooth_;
  // Rims (see nearest()): the edge a-b, the face kept flat along it and the curved face across it; per vertex (in
  // compressed rows) the rims that end there.
  struct Rim {
    std::int32_t a, b, flat_face, curved_face;
  };
  bool with_rims_ = true;
  std::vector<Rim> rims_;
  std::vector<std::size_t> rim_start_;
  std::vector<std::int32_t> rim_at_vertex_;

  void find_rims();
  // The curved face's lifted edge a-b at a + t (b - a), minus that point: Eq. (2) on the edge.
  Eigen::Vector3d rim_offset(const Rim& rim, double t) const;
  // The rim's answer for q (see nearest()) when it has one, replacing *best (squared distance *best_sq).
  // on_flat: *best is still s on a flat face (lift(s) did not move it).
  void apply_rim(const Rim& rim, const Eigen::Vector3d& q, const SurfacePoint& s, bool* on_flat, PhongPoint* best,
                 double* best_sq) const;
  // |ab x ac| times the unit normal of face f.
  Eigen::Vector3d face_normal_of(int f) const;
};

}  // namespace conform
