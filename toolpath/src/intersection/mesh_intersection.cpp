#include "conform/toolpath/intersection/mesh_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <omp.h>
#include <Eigen/Geometry>

#include "conform/core/error.h"

namespace conform {
namespace {

using Box = Eigen::AlignedBox3d;

Box face_box(const Mesh& mesh, const Face& f) {
  Box box(mesh.vertices[static_cast<std::size_t>(f[0])]);
  box.extend(mesh.vertices[static_cast<std::size_t>(f[1])]);
  box.extend(mesh.vertices[static_cast<std::size_t>(f[2])]);
  return box;
}

IndexedTriangle indexed(const Mesh& mesh, std::size_t face) {
  IndexedTriangle t;
  const Face& f = mesh.faces[face];
  for (int k = 0; k < 3; ++k) {
    t.index[k] = f[static_cast<std::size_t>(k)];
    t.p[k] = mesh.vertices[static_cast<std::size_t>(t.index[k])];
  }
  t.face = static_cast<std::int32_t>(face);
  return t;
}

void check_mesh(const Mesh& mesh, const char* what) {
  check_consistent(mesh, what);
  if (mesh.faces.empty()) throw Error(std::string(what) + " has no faces: the intersection needs triangle meshes");
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!v.allFinite()) throw Error(std::string(what) + " has a vertex that is not finite");
  }
}

// A uniform grid of B's triangles over a box, stored as compressed rows (cell -> faces).
class FaceGrid {
 public:
  FaceGrid(const Mesh& b, const Box& region, double cell) : origin_(region.min()), cell_(cell) {
    const Eigen::Vector3d extent = region.sizes();
    for (int k = 0; k < 3; ++k) dims_[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>(extent[k] / cell) + 1);
    start_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2] + 1), 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
      if (pass == 1) faces_.resize(static_cast<std::size_t>(start_.back()));
      for (std::size_t f = 0; f < b.faces.size(); ++f) {
        const Box box = face_box(b, b.faces[f]);
        if (!box.intersects(region)) continue;
        std::array<std::int64_t, 3> lo;
        std::array<std::int64_t, 3> hi;
        range(box, &lo, &hi);
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
            for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
              const std::size_t c = static_cast<std::size_t>(x + dims_[0] * (y + dims_[1] * z));
              if (pass == 0) {
                ++start_[c + 1];
              } else {
                faces_[static_cast<std::size_t>(fill[c]++)] = static_cast<std::int32_t>(f);
              }
            }
      }
      if (pass == 0) {
        for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
      }
    }
  }

  // Faces of every cell the box touches, sorted and without repeats.
  void candidates(const Box& box, std::vector<std::int32_t>* out) const {
    out->clear();
    std::array<std::int64_t, 3> lo;
    std::array<std::int64_t, 3> hi;
    range(box, &lo, &hi);
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t c = static_cast<std::size_t>(x + dims_[0] * (y + dims_[1] * z));
          out->insert(out->end(), faces_.begin() + start_[c], faces_.begin() + start_[c + 1]);
        }
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
  }

 private:
  void range(const Box& box, std::array<std::int64_t, 3>* lo, std::array<std::int64_t, 3>* hi) const {
    for (int k = 0; k < 3; ++k) {
      const auto cell = [&](double v) {
        const auto i = static_cast<std::int64_t>(std::floor((v - origin_[k]) / cell_));
        return std::clamp<std::int64_t>(i, 0, dims_[k] - 1);
      };
      (*lo)[static_cast<std::size_t>(k)] = cell(box.min()[k]);
      (*hi)[static_cast<std::size_t>(k)] = cell(box.max()[k]);
    }
  }

  Eigen::Vector3d origin_;
  double cell_;
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<std::int64_t> start_;
  std::vector<std::int32_t> faces_;
};

double mean_face_extent(const Mesh& mesh) {
  double sum = 0.0;
  for (const Face& f : mesh.faces) sum += face_box(mesh, f).sizes().maxCoeff();
  return sum / static_cast<double>(mesh.faces.size());
}

}  // namespace

bool MeshIntersectionOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(std::isfinite(cell_mm) && cell_mm >= 0.0))
    why << "grid cell " << cell_mm << " mm must be >= 0 (0: automatic)";
  else if (max_cells < 1)
    why << "max_cells " << max_cells << " must be >= 1";
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

MeshIntersectionResult intersect_meshes(const Mesh& a, const Mesh& b, const MeshIntersectionOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("mesh intersection: " + why);
  check_mesh(a, "mesh A (leg)");
  check_mesh(b, "mesh B (stub)");
  MeshIntersectionResult result;
  Box box_a;
  for (const Eigen::Vector3d& v : a.vertices) box_a.extend(v);
  Box box_b;
  for (const Eigen::Vector3d& v : b.vertices) box_b.extend(v);
  if (!box_a.intersects(box_b)) return result;
  const Box region = box_a.intersection(box_b);
  double cell = options.cell_mm > 0.0 ? options.cell_mm : 1.5 * mean_face_extent(b);
  cell = std::max(cell, 1e-9 + 1e-9 * region.sizes().maxCoeff());
  const auto cells = [&](double c) {
    const Eigen::Vector3d n = region.sizes() / c + Eigen::Vector3d::Ones();
    return n.x() * n.y() * n.z();
  };
  while (cells(cell) > static_cast<double>(options.max_cells)) cell *= 1.25;
  result.cell_mm = cell;
  const FaceGrid grid(b, region, cell);

  const auto faces_a = static_cast<std::int64_t>(a.faces.size());
  std::vector<std::vector<IntersectionSegment>> per_thread;
  std::vector<std::size_t> candidates_per_thread;
  std::vector<std::size_t> odd_per_thread;
#pragma omp parallel
  {
#pragma omp single
    {
      per_thread.resize(static_cast<std::size_t>(omp_get_num_threads()));
      candidates_per_thread.assign(per_thread.size(), 0);
      odd_per_thread.assign(per_thread.size(), 0);
    }
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    std::vector<IntersectionSegment>& out = per_thread[thread];
    std::vector<std::int32_t> candidates;
    EdgeCrossing ends[6];
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t fa = 0; fa < faces_a; ++fa) {
      const Box box = face_box(a, a.faces[static_cast<std::size_t>(fa)]);
      if (!box.intersects(region)) continue;
      grid.candidates(box, &candidates);
      if (candidates.empty()) continue;
      const IndexedTriangle ta = indexed(a, static_cast<std::size_t>(fa));
      for (const std::int32_t fb : candidates) {
        if (!box.intersects(face_box(b, b.faces[static_cast<std::size_t>(fb)]))) continue;
        ++candidates_per_thread[thread];
        const int count = intersect_triangles(ta, indexed(b, static_cast<std::size_t>(fb)), ends);
        if (count == 0) continue;
        if (count != 2) {
          ++odd_per_thread[thread];
          continue;
        }
        IntersectionSegment segment;
        segment.face_a = static_cast<std::int32_t>(fa);
        segment.face_b = fb;
        segment.ends[0] = ends[0];
        segment.ends[1] = ends[1];
        out.push_back(segment);
      }
    }
  }
  for (std::size_t t = 0; t < per_thread.size(); ++t) {
    result.segments.insert(result.segments.end(), per_thread[t].begin(), per_thread[t].end());
    result.candidate_pairs += candidates_per_thread[t];
    result.odd_pairs += odd_per_thread[t];
  }
  std::sort(result.segments.begin(), result.segments.end(), [](const auto& x, const auto& y) {
    return x.face_a != y.face_a ? x.face_a < y.face_a : x.face_b < y.face_b;
  });
  return result;
}

}  // namespace conform
