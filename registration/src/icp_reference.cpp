#include "conform/registration/icp_reference.h"

#include <cmath>
#include <cstdint>
#include <exception>
#include <future>
#include <mutex>
#include <string>
#include <utility>

#include <omp.h>

#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/normals.h"
#include "conform/core/phong_surface.h"

namespace conform {

namespace {

constexpr int kNormalNeighbours = 16;

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

IcpReference::IcpReference(const Mesh& reference) : surface_state_(std::make_unique<SurfaceState>()) {
  build(reference);
}
IcpReference::IcpReference(const Cloud& reference) : surface_state_(std::make_unique<SurfaceState>()) {
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
  const std::vector<std::uint32_t>& index_at = tree_->leaf_order();
  by_position_.resize(index_at.size());
  for (std::size_t p = 0; p < index_at.size(); ++p) {
    by_position_[p] = {mesh.vertices[index_at[p]], normals_[index_at[p]]};
  }
  points_ = std::move(mesh.vertices);
  faces_ = std::move(mesh.faces);
}

// The triangle index and the smooth surface: made once, by whichever comes first, prepare_surface()'s thread or the
// first surface() call (which then waits for it: std::call_once).
struct IcpReference::SurfaceState {
  std::once_flag once;
  std::unique_ptr<TriangleIndex> index;
  std::unique_ptr<PhongSurface> phong;
  std::future<void> pending;  // last: destroyed (joined) first

  // make_mesh() is called only by the one call that builds.
  template <typename MakeMesh>
  void build(const MakeMesh& make_mesh, const std::vector<Eigen::Vector3d>& normals) {
    std::call_once(once, [&] {
      const Mesh mesh = make_mesh();
      // The two are independent: the smooth surface on a second thread when OpenMP may use one (it costs about half
      // the index), joined before either is used. The reference's own normals at smooth vertices, so that the curved
      // surface is the one its normals describe.
      // Lifting only: the rims compare's nearest() needs are not found.
      const auto make_phong = [&] {
        phong = std::make_unique<PhongSurface>(mesh, normals, kDefaultCreaseAngleRad, false);
      };
      std::future<void> beside;
      if (omp_get_max_threads() >= 2) beside = std::async(std::launch::async, make_phong);
      index = std::make_unique<TriangleIndex>(mesh);
      if (beside.valid()) {
        beside.get();  // rethrows the smooth surface's error, if any
      } else {
        make_phong();
      }
    });
  }
};

Mesh IcpReference::surface_mesh() const {
  Mesh mesh;
  mesh.vertices = points_;
  mesh.faces = faces_;
  return mesh;
}

void IcpReference::prepare_surface() const {
  if (faces_.empty() || omp_get_max_threads() < 2 || surface_state_->pending.valid()) return;
  // Copies, so that the thread does not depend on this object (which may be moved meanwhile).
  surface_state_->pending =
      std::async(std::launch::async, [state = surface_state_.get(), mesh = surface_mesh(), normals = normals_] {
        try {
          state->build([&mesh]() -> const Mesh& { return mesh; }, normals);
        } catch (const std::exception&) {
          // surface() builds again on the caller's thread and throws there.
        }
      });
}

const TriangleIndex& IcpReference::surface() const {
  if (faces_.empty()) {
    throw Error(
        "point-to-surface ICP needs a reference mesh with faces; this reference is a point cloud (use "
        "point-to-plane)");
  }
  // Only point-to-surface needs it, and building it costs more than the kd-tree.
  surface_state_->build([this] { return surface_mesh(); }, normals_);
  return *surface_state_->index;
}

const PhongSurface& IcpReference::phong() const {
  surface();
  return *surface_state_->phong;
}

const std::vector<unsigned char>& IcpReference::smooth() const {
  static const std::vector<unsigned char> none;
  return faces_.empty() ? none : phong().smooth();
}

}  // namespace conform
