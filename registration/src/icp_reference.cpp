#include "conform/registration/icp_reference.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/normals.h"

namespace conform {

namespace {

constexpr int kNormalNeighbours = 16;
// A vertex whose normal is more than this from one of its faces' normals sits on a crease (its faces meet at up to
// twice the angle): a CAD edge, a box's corner. 30 deg, chosen on seed sweeps (docs/align.md): 20 also took the
// ribbed plate's steep rib ends (under-sampled by its mesh) for creases (0.010-0.020 mm off along the ribs against
// 0.002-0.010), 40 rounded the box part's 45 deg chamfer (0.002-0.004 mm against 0.001-0.002); a 4 mm mesh of a
// 150 mm radius (1.5 deg between neighbouring faces) is smooth.
const double kCreaseCosine = std::cos(30.0 * M_PI / 180.0);

// Which vertices have every incident face within the crease angle of their normal.
std::vector<unsigned char> smooth_vertices(const Mesh& mesh, const std::vector<Eigen::Vector3d>& normals) {
  std::vector<unsigned char> smooth(mesh.vertices.size(), 0);
  std::vector<unsigned char> creased(mesh.vertices.size(), 0);
  for (const Face& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d n =
        (mesh.vertices[static_cast<std::size_t>(f[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(f[2])] - a);
    const double area2 = n.norm();
    for (std::int32_t i : f) {
      const auto v = static_cast<std::size_t>(i);
      smooth[v] = 1;
      // A face without area says nothing about the surface's shape.
      if (area2 > 0.0 && std::abs(normals[v].dot(n)) < kCreaseCosine * area2) creased[v] = 1;
    }
  }
  for (std::size_t v = 0; v < smooth.size(); ++v) smooth[v] = smooth[v] && !creased[v] ? 1 : 0;
  return smooth;
}

// PCA normals of a cloud without faces, over the tree already built on it, turned away from its centroid: the sign
// does not matter to point-to-plane distances, but a consistent one keeps features (FPFH) comparable between scan
// and reference.
std::vector<Eigen::Vector3d> cloud_normals(const Mesh& mesh, const KdTree& tree) {
  NormalOptions options;
  options.k = kNormalNeighbours;
  options.viewpoint = centroid(mesh);
  const pcl::PointCloud<pcl::Normal> normals = estimate_normals(tree, options);
  std::vector<Eigen::Vector3d> out(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) out[i] = -normals[i].getNormalVector3fMap().cast<double>();
  return out;
}

}  // namespace

IcpReference::IcpReference(const Mesh& reference) { build(reference); }
IcpReference::IcpReference(const Cloud& reference) {
  check_consistent(reference, "ICP reference");
  build(to_mesh(reference));
}
IcpReference::~IcpReference() = default;
IcpReference::IcpReference(IcpReference&&) noexcept = default;
IcpReference& IcpReference::operator=(IcpReference&&) noexcept = default;

void IcpReference::build(Mesh mesh) {
  check_consistent(mesh, "ICP reference");
  if (mesh.vertices.size() < 3) {
    throw Error("ICP reference: " + std::to_string(mesh.vertices.size()) + " points; at least 3 are needed");
  }
  if (count_non_finite(mesh) > 0) throw Error("ICP reference: has NaN or infinite points; clean it first");
  // The tree first: a cloud's normals are estimated over it.
  tree_ = std::make_unique<KdTree>(mesh.vertices);
  if (mesh.has_normals()) {
    normals_ = std::move(mesh.normals);
    for (Eigen::Vector3d& n : normals_) {
      const double length = n.norm();
      n = length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
    }
  } else if (mesh.has_faces()) {
    // Area-weighted face normals rather than PCA: a CAD mesh's few large triangles would put a whole face (and its
    // neighbours) into 16 neighbours. Isolated vertices get a zero normal and so add nothing to a plane step.
    normals_ = vertex_normals_from_faces(mesh);
  } else {
    normals_ = cloud_normals(mesh, *tree_);
  }
  if (mesh.has_faces()) smooth_ = smooth_vertices(mesh, normals_);
  const std::vector<std::uint32_t>& index_at = tree_->leaf_order();
  by_position_.resize(index_at.size());
  for (std::size_t p = 0; p < index_at.size(); ++p) {
    by_position_[p] = {mesh.vertices[index_at[p]], normals_[index_at[p]]};
  }
  points_ = std::move(mesh.vertices);
  faces_ = std::move(mesh.faces);
}

const TriangleIndex& IcpReference::surface() const {
  if (faces_.empty()) {
    throw Error(
        "point-to-surface ICP needs a reference mesh with faces; this reference is a point cloud (use "
        "point-to-plane)");
  }
  // Only point-to-surface needs it, and building it costs more than the kd-tree.
  std::call_once(*surface_once_, [this] {
    Mesh mesh;
    mesh.vertices = points_;
    mesh.faces = faces_;
    surface_ = std::make_unique<TriangleIndex>(mesh);
  });
  return *surface_;
}

}  // namespace conform
