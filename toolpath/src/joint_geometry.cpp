#include "conform/toolpath/joint_geometry.h"

#include <algorithm>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/toolpath/local_quadric.h"

namespace conform {
namespace {

Eigen::Vector3d radial(const Eigen::Vector3d& p, const TubeAxis& axis) {
  const Eigen::Vector3d d = p - axis.point;
  return d - d.dot(axis.direction) * axis.direction;
}

std::vector<Eigen::Vector3d> neighbours(const KdTree& tree, const Mesh& mesh, const Eigen::Vector3d& p, int k) {
  std::vector<int> indices;
  std::vector<float> sq;
  tree.knn(p.cast<float>(), k, indices, sq);
  std::vector<Eigen::Vector3d> out;
  out.reserve(indices.size());
  for (const int i : indices) out.push_back(mesh.vertices[static_cast<std::size_t>(i)]);
  return out;
}

}  // namespace

bool JointGeometryOptions::IsValid(std::string* error) const {
  std::string why;
  if (k_normals < 3)
    why = "k-normals " + std::to_string(k_normals) + " must be >= 3";
  else if (k_refine != 0 && k_refine < 6)
    why = "k-refine " + std::to_string(k_refine) + " must be 0 (off) or >= 6";
  else if (!(max_refine_mm > 0.0))
    why = "the largest refinement move must be > 0 mm";
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

Eigen::Vector3d pca_normal(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p, const TubeAxis& axis,
                           NormalFit fit) {
  const LocalQuadric patch = fit_local_quadric(points, p, fit == NormalFit::kQuadric);
  Eigen::Vector3d normal = patch.gradient(p).normalized();
  if (normal.dot(radial(p, axis)) < 0.0) normal = -normal;
  return normal;
}

bool refine_seam_point(const LocalQuadric& stub, const LocalQuadric& leg, double max_move_mm, Eigen::Vector3d* p) {
  const double rho0 = p->head<2>().norm();
  if (!(rho0 > 0.0)) return false;
  const Eigen::Vector3d e_rho(p->x() / rho0, p->y() / rho0, 0.0);
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d q = *p;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::Vector3d gs = stub.gradient(q);
    const Eigen::Vector3d gl = leg.gradient(q);
    Eigen::Matrix2d J;
    J << gs.dot(e_rho), gs.dot(e_z), gl.dot(e_rho), gl.dot(e_z);
    if (std::abs(J.determinant()) < 1e-9) return false;
    const Eigen::Vector2d step = J.partialPivLu().solve(-Eigen::Vector2d(stub.height(q), leg.height(q)));
    q += step(0) * e_rho + step(1) * e_z;
    if (step.norm() < 1e-9) break;
  }
  if (!q.allFinite() || (q - *p).norm() > max_move_mm) return false;
  *p = q;
  return true;
}

PathFrame path_frame(double phi_rad, const Eigen::Vector3d& p, const Eigen::Vector3d& stub_normal,
                     const Eigen::Vector3d& leg_normal) {
  PathFrame frame;
  frame.phi_rad = phi_rad;
  frame.point = p;
  frame.stub_normal = stub_normal;
  frame.leg_normal = leg_normal;
  const Eigen::Vector3d t = stub_normal.cross(leg_normal);  // Eq. (3)
  if (t.norm() < 1e-9) {
    std::ostringstream what;
    what << "the stub and leg normals are parallel at azimuth " << phi_rad * 57.29577951308232
         << " deg: the surfaces touch instead of crossing";
    throw Error(what.str());
  }
  frame.tangent = t.normalized();
  frame.leg_out = leg_normal.cross(frame.tangent);  // Eq. (6)
  return frame;
}

std::vector<PathFrame> joint_geometry(const std::vector<double>& phi_rad, const std::vector<Eigen::Vector3d>& points,
                                      const Mesh& stub_S, const TubeAxis& stub_axis, const Mesh& leg_S,
                                      const TubeAxis& leg_axis, const JointGeometryOptions& options,
                                      std::size_t* refined) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("joint geometry: " + why);
  const auto k = static_cast<std::size_t>(options.k_normals);
  if (stub_S.vertices.size() < k || leg_S.vertices.size() < k) {
    throw Error("joint geometry: a mesh has fewer vertices than k-normals (" + std::to_string(k) + ")");
  }
  const KdTree stub_tree(stub_S.vertices);
  const KdTree leg_tree(leg_S.vertices);
  std::vector<PathFrame> frames(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector3d p = points[i];
    if (options.k_refine > 0) {
      const bool quadric = options.fit == NormalFit::kQuadric;
      const LocalQuadric stub = fit_local_quadric(neighbours(stub_tree, stub_S, p, options.k_refine), p, quadric);
      const LocalQuadric leg = fit_local_quadric(neighbours(leg_tree, leg_S, p, options.k_refine), p, quadric);
      // The fits hold within their patches: a move up to half the smaller patch's radius is trusted.
      const double limit = std::max(options.max_refine_mm, 0.5 * std::min(stub.scale, leg.scale));
      if (!refine_seam_point(stub, leg, limit, &p)) {
        p = points[i];
      } else if (refined != nullptr) {
        ++*refined;
      }
    }
    const Eigen::Vector3d n_s =
        pca_normal(neighbours(stub_tree, stub_S, p, options.k_normals), p, stub_axis, options.fit);
    const Eigen::Vector3d n_l = pca_normal(neighbours(leg_tree, leg_S, p, options.k_normals), p, leg_axis, options.fit);
    frames[i] = path_frame(phi_rad[i], p, n_s, n_l);
  }
  return frames;
}

}  // namespace conform
