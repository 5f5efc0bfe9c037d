#include "conform/toolpath/intersection/joint_geometry.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/toolpath/intersection/local_quadric.h"
#include "conform/toolpath/intersection/scan_quality.h"

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

// The fit's unit normal at p, away from the tube's axis.
Eigen::Vector3d oriented(const LocalQuadric& patch, const Eigen::Vector3d& p, const TubeAxis& axis) {
  Eigen::Vector3d normal = patch.gradient(p).normalized();
  if (normal.dot(radial(p, axis)) < 0.0) normal = -normal;
  return normal;
}

}  // namespace

bool JointGeometryOptions::IsValid(std::string* error) const {
  std::string why;
  if (k_normals != 0 && k_normals < 3)
    why = "k-normals " + std::to_string(k_normals) + " must be 0 (sized to the noise) or >= 3";
  else if (k_refine > 0 && k_refine < 6)
    why = "k-refine " + std::to_string(k_refine) + " must be < 0 (the normals'), 0 (off) or >= 6";
  else if (!(target_normal_deg > 0.0 && target_normal_deg <= 10.0) ||
           !(target_tangent_deg > 0.0 && target_tangent_deg <= 10.0))
    why = "the target normal and tangent errors must be in (0, 10] deg";
  else if (!(max_refine_mm > 0.0))
    why = "the largest refinement move must be > 0 mm";
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

Eigen::Vector3d pca_normal(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p, const TubeAxis& axis,
                           NormalFit fit) {
  return oriented(fit_local_quadric(points, p, fit == NormalFit::kQuadric), p, axis);
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

int sized_normal_count(double noise_mm, double edge_mm, const JointGeometryOptions& options) {
  if (options.k_normals > 0) return options.k_normals;
  const double theta = options.target_normal_deg * kPi / 180.0;
  const double n = edge_mm > 0.0 ? 3.8 * noise_mm / (edge_mm * theta) : 0.0;
  return static_cast<int>(
      std::clamp(std::ceil(n), double(JointGeometryOptions::kMinNormals), double(JointGeometryOptions::kMaxNormals)));
}

std::vector<PathFrame> joint_geometry(const std::vector<double>& phi_rad, const std::vector<Eigen::Vector3d>& points,
                                      const Mesh& stub_S, const TubeAxis& stub_axis, const Mesh& leg_S,
                                      const TubeAxis& leg_axis, const JointGeometryOptions& options,
                                      std::size_t* refined) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("joint geometry: " + why);
  // The neighbourhood of each mesh: given, or sized to its noise and edges near the path.
  int k_stub = options.k_normals, k_leg = options.k_normals;
  if (options.k_normals == 0) {
    const int probe =
        static_cast<int>(std::min<std::size_t>(40, std::min(stub_S.vertices.size(), leg_S.vertices.size())));
    if (probe < 6) throw Error("joint geometry: a mesh has fewer than 6 vertices");
    const ScanQuality qs = estimate_scan_quality(stub_S, points, probe, 96);
    const ScanQuality ql = estimate_scan_quality(leg_S, points, probe, 96);
    k_stub = sized_normal_count(qs.noise_mm, qs.edge_mm, options);
    k_leg = sized_normal_count(ql.noise_mm, ql.edge_mm, options);
  }
  k_stub = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(k_stub), stub_S.vertices.size()));
  k_leg = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(k_leg), leg_S.vertices.size()));
  if (k_stub < 3 || k_leg < 3 ||
      (options.k_normals > 0 && (stub_S.vertices.size() < static_cast<std::size_t>(options.k_normals) ||
                                 leg_S.vertices.size() < static_cast<std::size_t>(options.k_normals)))) {
    throw Error("joint geometry: a mesh has fewer vertices than k-normals (" + std::to_string(options.k_normals) + ")");
  }
  const int refine_stub = options.k_refine < 0 ? std::max(k_stub, 6) : options.k_refine;
  const int refine_leg = options.k_refine < 0 ? std::max(k_leg, 6) : options.k_refine;
  const KdTree stub_tree(stub_S.vertices);
  const KdTree leg_tree(leg_S.vertices);
  std::vector<PathFrame> frames(points.size());
  const bool quadric = options.fit == NormalFit::kQuadric;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector3d p = points[i];
    if (options.k_refine != 0) {
      const LocalQuadric stub = fit_local_quadric(neighbours(stub_tree, stub_S, p, refine_stub), p, quadric);
      const LocalQuadric leg = fit_local_quadric(neighbours(leg_tree, leg_S, p, refine_leg), p, quadric);
      // The fits hold within their patches: a move up to half the smaller patch's radius is trusted.
      const double limit = std::max(options.max_refine_mm, 0.5 * std::min(stub.scale, leg.scale));
      if (!refine_seam_point(stub, leg, limit, &p)) {
        p = points[i];
      } else if (refined != nullptr) {
        ++*refined;
      }
    }
    // Where the surfaces cross at a grazing angle Eq. (3) amplifies the normals' noise by 1 / sin(beta): with sized
    // neighbourhoods (k_normals = 0) the fits there grow (the noise error falls as 1 / N) until the tangent's is
    // target_tangent_deg, or the neighbourhood kMaxNormals.
    int ks = k_stub, kl = k_leg;
    for (int round = 0; round < 2; ++round) {
      const LocalQuadric fs = fit_local_quadric(neighbours(stub_tree, stub_S, p, ks), p, quadric);
      const LocalQuadric fl = fit_local_quadric(neighbours(leg_tree, leg_S, p, kl), p, quadric);
      frames[i] = path_frame(phi_rad[i], p, oriented(fs, p, stub_axis), oriented(fl, p, leg_axis));
      const double sin_beta = std::max(frames[i].stub_normal.cross(frames[i].leg_normal).norm(), 1e-6);
      frames[i].stub_normal_sigma_deg = fs.normal_sigma_rad * 180.0 / kPi;
      frames[i].leg_normal_sigma_deg = fl.normal_sigma_rad * 180.0 / kPi;
      // Only the normals' tilt across the seam turns t by 1 / sin(beta): one of the two components of each sigma.
      frames[i].tangent_sigma_deg =
          std::hypot(frames[i].stub_normal_sigma_deg, frames[i].leg_normal_sigma_deg) / (std::sqrt(2.0) * sin_beta);
      const double ratio = frames[i].tangent_sigma_deg / options.target_tangent_deg;
      if (options.k_normals != 0 || ratio <= 1.0) break;
      auto grown = [&](int k, std::size_t size) {
        return static_cast<int>(std::min<double>(
            {std::ceil(k * ratio), double(JointGeometryOptions::kMaxNormals), static_cast<double>(size)}));
      };
      const int ks2 = grown(ks, stub_S.vertices.size()), kl2 = grown(kl, leg_S.vertices.size());
      if (ks2 == ks && kl2 == kl) break;
      ks = ks2, kl = kl2;
    }
  }
  return frames;
}

}  // namespace conform
