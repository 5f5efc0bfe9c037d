#include "conform/core/phong_surface.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conform/core/error.h"
#include "conform/core/planar_regions.h"

namespace conform {

namespace {

// Phong tessellation's shape factor: 1/2 reproduces quadratic surfaces (Boubekeur & Alexa 2008, Sec. 3).
constexpr double kPhongShape = 0.5;
// A corner normal this close to the face's own leaves the face flat there (rounding of coplanar faces' normals).
constexpr double kFlatCosine = 1.0 - 1e-9;

const Eigen::Vector3d& vertex(const Mesh& mesh, std::int32_t i) { return mesh.vertices[static_cast<std::size_t>(i)]; }

// |ab x ac| times the unit normal of each face (zero for a face without area).
std::vector<Eigen::Vector3d> scaled_face_normals(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> out(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    const Eigen::Vector3d& a = vertex(mesh, face[0]);
    out[f] = (vertex(mesh, face[1]) - a).cross(vertex(mesh, face[2]) - a);
    if (!out[f].allFinite()) out[f].setZero();
  }
  return out;
}

// The interior angle of face f at its k-th corner, rad.
double corner_angle(const Mesh& mesh, const Face& face, int k) {
  const Eigen::Vector3d& p = vertex(mesh, face[static_cast<std::size_t>(k)]);
  const Eigen::Vector3d u = vertex(mesh, face[static_cast<std::size_t>((k + 1) % 3)]) - p;
  const Eigen::Vector3d v = vertex(mesh, face[static_cast<std::size_t>((k + 2) % 3)]) - p;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& n) {
  const double length = n.norm();
  return length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

void check_faces(const Mesh& mesh) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (std::int32_t i : mesh.faces[f]) {
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size()) {
        throw Error("smooth surface: face " + std::to_string(f) + " has vertex index " + std::to_string(i) +
                    " out of range");
      }
    }
  }
}

}  // namespace

std::vector<unsigned char> smooth_vertices(const Mesh& mesh, const std::vector<Eigen::Vector3d>& normals,
                                           double crease_angle_rad) {
  const double crease_cosine = std::cos(crease_angle_rad);
  const std::size_t n = mesh.vertices.size();
  // Each vertex's faces with their unit normals; faces without area say nothing about the shape.
  const VertexFaces rows = faces_around_vertices(mesh);
  const std::vector<std::size_t>& start = rows.start;
  std::vector<Eigen::Vector3d> around(rows.faces.size());
  for (std::size_t j = 0; j < around.size(); ++j) {
    const Face& f = mesh.faces[rows.faces[j]];
    const Eigen::Vector3d& a = vertex(mesh, f[0]);
    around[j] = unit_or_zero((vertex(mesh, f[1]) - a).cross(vertex(mesh, f[2]) - a));
  }
  std::vector<unsigned char> smooth(n, 0);
  for (std::size_t v = 0; v < n; ++v) {
    bool ok = start[v + 1] > start[v];
    // Every face within the crease angle of the vertex normal and of every other face (a 45 deg chamfer is a crease
    // even though the averaged normal is 22.5 deg from both sides).
    for (std::size_t j = start[v]; ok && j < start[v + 1]; ++j) {
      if (around[j].isZero()) continue;
      ok = std::abs(normals[v].dot(around[j])) >= crease_cosine;
      for (std::size_t k = j + 1; ok && k < start[v + 1]; ++k) {
        ok = around[k].isZero() || std::abs(around[j].dot(around[k])) >= crease_cosine;
      }
    }
    smooth[v] = ok ? 1 : 0;
  }
  return smooth;
}

PhongSurface::PhongSurface(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normals,
                           double crease_angle_rad, bool with_rims)
    : vertices_(mesh.vertices), faces_(mesh.faces), with_rims_(with_rims) {
  check_faces(mesh);
  const std::size_t n = mesh.vertices.size();
  if (!vertex_normals.empty() && vertex_normals.size() != n) {
    throw Error("smooth surface: " + std::to_string(vertex_normals.size()) + " normals for " + std::to_string(n) +
                " vertices");
  }
  const std::vector<Eigen::Vector3d> face_normals = scaled_face_normals(mesh);
  normals_ = vertex_normals;
  for (Eigen::Vector3d& v : normals_) v = unit_or_zero(v);
  if (normals_.empty()) {
    normals_.assign(n, Eigen::Vector3d::Zero());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const Eigen::Vector3d u = unit_or_zero(face_normals[f]);
      for (int k = 0; k < 3; ++k) {
        normals_[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])] +=
            corner_angle(mesh, mesh.faces[f], k) * u;
      }
    }
    for (Eigen::Vector3d& v : normals_) v = unit_or_zero(v);
  }
  smooth_ = smooth_vertices(mesh, normals_, crease_angle_rad);
  const std::vector<unsigned char> flat = planar_faces(mesh, crease_angle_rad);

  const VertexFaces rows = faces_around_vertices(mesh);
  const std::vector<std::size_t>& start = rows.start;
  const std::vector<std::size_t>& around = rows.faces;

  const double crease_cosine = std::cos(crease_angle_rad);
  // The angle-weighted normal of the faces around v within the crease angle of `own` (all of them, or only the
  // planes'); zero when there are none.
  const auto side_normal = [&](std::int32_t v, const Eigen::Vector3d& own, bool planes_only) {
    const auto vu = static_cast<std::size_t>(v);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t j = start[vu]; j < start[vu + 1]; ++j) {
      const std::size_t g = around[j];
      if (planes_only && !flat[g]) continue;
      const Eigen::Vector3d other = unit_or_zero(face_normals[g]);
      if (other.dot(own) < crease_cosine) continue;
      const Face& gf = mesh.faces[g];
      const int corner = gf[0] == v ? 0 : gf[1] == v ? 1 : 2;
      sum += corner_angle(mesh, gf, corner) * other;
    }
    return unit_or_zero(sum);
  };
  corners_.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d own = unit_or_zero(face_normals[f]);
    if (flat[f]) {
      // A plane's face stays flat (core/planar_regions.h).
      const auto index = static_cast<std::int32_t>(normals_.size());
      normals_.push_back(own);
      corners_[f] = {index, index, index};
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = mesh.faces[f][static_cast<std::size_t>(k)];
      corners_[f][static_cast<std::size_t>(k)] = v;
      // Where a curved face meets a plane within the crease angle, the junction is tangent and the surface normal
      // there is the plane's; otherwise at a crease, the faces on this face's side of it.
      Eigen::Vector3d corner = side_normal(v, own, true);
      if (corner.isZero()) {
        if (smooth_[static_cast<std::size_t>(v)]) continue;
        corner = side_normal(v, own, false);
      }
      corners_[f][static_cast<std::size_t>(k)] = static_cast<std::int32_t>(normals_.size());
      normals_.push_back(corner);
    }
  }
  if (with_rims_) find_rims();
}

Eigen::Vector3d PhongSurface::face_normal_of(int f) const {
  const Face& face = faces_[static_cast<std::size_t>(f)];
  const Eigen::Vector3d& a = vertices_[static_cast<std::size_t>(face[0])];
  return (vertices_[static_cast<std::size_t>(face[1])] - a).cross(vertices_[static_cast<std::size_t>(face[2])] - a);
}

void PhongSurface::find_rims() {
  // Every edge with its face, sorted so that the two faces of an edge are adjacent.
  struct Side {
    std::int32_t a, b, face;
  };
  std::vector<Side> sides;
  sides.reserve(3 * faces_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = faces_[f][static_cast<std::size_t>(k)],
                         j = faces_[f][static_cast<std::size_t>((k + 1) % 3)];
      sides.push_back({std::min(i, j), std::max(i, j), static_cast<std::int32_t>(f)});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
  });
  // Face f is flat along a-b when its corners there use its own normal (or none), as lift() sees them.
  const auto flat_along = [&](std::int32_t f, std::int32_t a, std::int32_t b) {
    const auto fu = static_cast<std::size_t>(f);
    const Face& face = faces_[fu];
    const Eigen::Vector3d own = unit_or_zero(face_normal_of(f));
    for (int k = 0; k < 3; ++k) {
      if (face[static_cast<std::size_t>(k)] != a && face[static_cast<std::size_t>(k)] != b) continue;
      const Eigen::Vector3d& n = corner_normal(fu, k);
      if (!n.isZero() && std::abs(n.dot(own)) < kFlatCosine) return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b) ++j;
    if (j - i == 2) {
      const Side& x = sides[i];
      const Side& y = sides[i + 1];
      const bool x_flat = flat_along(x.face, x.a, x.b), y_flat = flat_along(y.face, x.a, x.b);
      if (x_flat != y_flat) {
        const Rim rim{x.a, x.b, x_flat ? x.face : y.face, x_flat ? y.face : x.face};
        if (!rim_offset(rim, 0.5).isZero()) rims_.push_back(rim);
      }
    }
    i = j;
  }
  rim_start_.assign(vertices_.size() + 1, 0);
  for (const Rim& r : rims_) {
    ++rim_start_[static_cast<std::size_t>(r.a) + 1];
    ++rim_start_[static_cast<std::size_t>(r.b) + 1];
  }
  for (std::size_t v = 0; v < vertices_.size(); ++v) rim_start_[v + 1] += rim_start_[v];
  rim_at_vertex_.resize(rim_start_.back());
  std::vector<std::size_t> fill(rim_start_.begin(), rim_start_.end() - 1);
  for (std::size_t r = 0; r < rims_.size(); ++r) {
    for (std::int32_t v : {rims_[r].a, rims_[r].b}) {
      rim_at_vertex_[fill[static_cast<std::size_t>(v)]++] = static_cast<std::int32_t>(r);
    }
  }
}

Eigen::Vector3d PhongSurface::rim_offset(const Rim& rim, double t) const {
  const auto f = static_cast<std::size_t>(rim.curved_face);
  const Face& face = faces_[f];
  const Eigen::Vector3d own = unit_or_zero(face_normal_of(rim.curved_face));
  const Eigen::Vector3d& ra = vertices_[static_cast<std::size_t>(rim.a)];
  const Eigen::Vector3d x = ra + t * (vertices_[static_cast<std::size_t>(rim.b)] - ra);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const std::int32_t v = face[static_cast<std::size_t>(k)];
    const Eigen::Vector3d& corner = corner_normal(f, k);
    if ((v != rim.a && v != rim.b) || corner.isZero()) continue;
    const Eigen::Vector3d n = corner.dot(own) < 0.0 ? Eigen::Vector3d(-corner) : corner;
    const double weight = v == rim.a ? 1.0 - t : t;
    offset += weight * (x - vertices_[static_cast<std::size_t>(v)]).dot(n) * n;
  }
  return -kPhongShape * offset;
}

void PhongSurface::apply_rim(const Rim& rim, const Eigen::Vector3d& q, const SurfacePoint& s, bool* on_flat,
                             PhongPoint* best, double* best_sq) const {
  const Face& flat = faces_[static_cast<std::size_t>(rim.flat_face)];
  const auto at = [&](std::int32_t i) -> const Eigen::Vector3d& { return vertices_[static_cast<std::size_t>(i)]; };
  const Eigen::Vector3d normal = unit_or_zero(face_normal_of(rim.flat_face));
  const Eigen::Vector3d& a = at(rim.a);
  const Eigen::Vector3d edge = at(rim.b) - a;
  if (normal.isZero()) return;
  const double height = (q - a).dot(normal);
  const Eigen::Vector3d on_plane = q - height * normal;
  const double t = (on_plane - a).dot(edge) / edge.squaredNorm();
  if (!(t > 0.0 && t < 1.0)) return;
  // Across the edge, out of the flat face, in its plane.
  Eigen::Vector3d out = unit_or_zero(edge.cross(normal));
  const std::int32_t third = flat[0] != rim.a && flat[0] != rim.b   ? flat[0]
                             : flat[1] != rim.a && flat[1] != rim.b ? flat[1]
                                                                    : flat[2];
  if ((at(third) - a).dot(out) > 0.0) out = -out;
  const double across = (on_plane - a - t * edge).dot(out);
  const double bulge = rim_offset(rim, t).dot(out);
  if (bulge > 0.0 && across > 0.0 && across <= bulge) {
    // Over the sliver the flat face's plane reaches to the curve: the plane is the surface there. Outside it, the
    // plane is the answer even when the curved side's lifted edge comes nearer: that edge may leave the plane by a
    // little (the side's normals at the rim lean out of it on a mesh that is not exact), by no more than the bulge.
    const bool outside = height >= 0.0;
    if (outside ? height <= std::sqrt(*best_sq) + bulge : height * height < *best_sq) {
      best->point = on_plane;
      best->normal = normal;
      best->lifted = true;
      *best_sq = height * height;
      *on_flat = false;
    }
  } else if (bulge < 0.0 && across < 0.0 && across >= bulge) {
    // Over the part of the flat face the curve cuts off: no surface there; the curved face is.
    const Face& curved = faces_[static_cast<std::size_t>(rim.curved_face)];
    SurfacePoint c = closest_point_on_triangle(q, at(curved[0]), at(curved[1]), at(curved[2]));
    c.face = rim.curved_face;
    const PhongPoint p = lift(c);
    if (!p.lifted) return;
    const double sq = (q - p.point).squaredNorm();
    const bool on_this_plane = *on_flat && unit_or_zero(face_normal_of(s.face)).dot(normal) >= kFlatCosine;
    if (on_this_plane || sq < *best_sq) {
      *best = p;
      *best_sq = sq;
      *on_flat = false;
    }
  }
}

PhongPoint PhongSurface::nearest(const Eigen::Vector3d& q, const SurfacePoint& s) const {
  if (!with_rims_) throw Error("smooth surface: nearest() on a surface built without its rims");
  PhongPoint best = lift(s);
  if (rims_.empty()) return best;
  bool on_flat = !best.lifted;
  double best_sq = best.lifted ? (q - best.point).squaredNorm() : s.sq_distance;
  for (std::int32_t v : faces_[static_cast<std::size_t>(s.face)]) {
    for (std::size_t j = rim_start_[static_cast<std::size_t>(v)]; j < rim_start_[static_cast<std::size_t>(v) + 1];
         ++j) {
      apply_rim(rims_[static_cast<std::size_t>(rim_at_vertex_[j])], q, s, &on_flat, &best, &best_sq);
    }
  }
  return best;
}

// Eq. (2)-(3), Boubekeur & Alexa 2008, shape factor 1/2: s moves by half the barycentric mean of its offsets to the
// tangent planes of the face's corners, and the normal is the barycentric mean of theirs.
PhongPoint PhongSurface::lift(const SurfacePoint& s) const {
  PhongPoint out;
  out.point = s.point;
  const auto f = static_cast<std::size_t>(s.face);
  const Face& face = faces_[f];
  const Eigen::Vector3d& a = vertices_[static_cast<std::size_t>(face[0])];
  Eigen::Vector3d face_normal =
      (vertices_[static_cast<std::size_t>(face[1])] - a).cross(vertices_[static_cast<std::size_t>(face[2])] - a);
  const double area2 = face_normal.norm();
  if (!(area2 > 0.0 && std::isfinite(area2))) return out;
  face_normal /= area2;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& corner = corner_normal(f, k);
    const double cosine = corner.dot(face_normal);
    if (corner.isZero()) {
      normal += s.barycentric[k] * face_normal;
      continue;
    }
    const Eigen::Vector3d n = cosine < 0.0 ? Eigen::Vector3d(-corner) : corner;
    out.lifted = out.lifted || std::abs(cosine) < kFlatCosine;
    offset += s.barycentric[k] *
              (s.point - vertices_[static_cast<std::size_t>(face[static_cast<std::size_t>(k)])]).dot(n) * n;
    normal += s.barycentric[k] * n;
  }
  out.normal = unit_or_zero(normal);
  if (out.normal.isZero()) {
    out.lifted = false;
    return out;
  }
  out.point = s.point - kPhongShape * offset;
  return out;
}

}  // namespace conform
