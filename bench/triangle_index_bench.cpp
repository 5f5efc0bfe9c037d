// Closest point on a triangle mesh (what point-to-surface ICP and `conform compare` ask once per scan point):
// conform::TriangleIndex (a BVH over the triangles) against VTK 9's vtkStaticCellLocator (FindClosestPoint, the
// thread-safe overload with a vtkGenericCell per thread), the peer a metrology tool built on VTK would use.
// Mesh: a generated closed tube (R 100 mm, 500 mm long, an ovality and a bump, 20 um noise) of about 1M triangles.
// Queries: 1M points within +-2 mm of the surface (a scan against its reference). Build time (best of 2) and
// queries per second with 1 and 2 threads (std::thread, the queries split in halves; wall clock, best of 2).
// Ratios > 1 mean the peer is slower. Afterwards, the largest difference of the two answers' distances.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <thread>
#include <vector>

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include "bench_timer.h"
#include "conform/core/triangle_index.h"
#include "conform/datasets/tube.h"

namespace {

using conform::bench::best_seconds;

conform::Mesh tube_mesh() {
  conform::TubeOptions t;
  t.radius_mm = 100.0;
  t.length_mm = 500.0;
  t.vertex_count = 500000;
  t.ovality_mm = 0.8;
  t.bumps.push_back({0.5, 40.0, 1.5, 30.0});
  t.noise_mm = 0.02;
  t.seed = 5;
  return conform::generate_tube(t).mesh;
}

// Uniform over the faces (not by area: the triangles are near-equal), uniform inside each, +-2 mm along its normal.
std::vector<Eigen::Vector3d> queries_near(const conform::Mesh& mesh, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> face(0, mesh.faces.size() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0), offset(-2.0, 2.0);
  std::vector<Eigen::Vector3d> queries(n);
  for (Eigen::Vector3d& q : queries) {
    const std::size_t f = face(rng);
    const conform::Face& t = mesh.faces[f];
    const double s = std::sqrt(u(rng)), w = u(rng);
    q = (1 - s) * mesh.vertices[t[0]] + s * (1 - w) * mesh.vertices[t[1]] + s * w * mesh.vertices[t[2]] +
        offset(rng) * conform::face_normal(mesh, f);
  }
  return queries;
}

// Runs body(begin, end) over [0, n) on `threads` threads, contiguous slices.
void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t, std::size_t)>& body) {
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back(body, n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads),
                      n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads));
  }
  for (std::thread& thread : pool) thread.join();
}

vtkSmartPointer<vtkPolyData> to_vtk(const conform::Mesh& mesh) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const Eigen::Vector3d& v : mesh.vertices) points->InsertNextPoint(v.x(), v.y(), v.z());
  vtkNew<vtkCellArray> cells;
  for (const conform::Face& f : mesh.faces) {
    const vtkIdType ids[3] = {f[0], f[1], f[2]};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

struct Row {
  double build_s = 0.0;
  double one_thread_s = 0.0;
  double two_threads_s = 0.0;
};

void print_row(const char* name, const Row& r, std::size_t queries) {
  const auto n = static_cast<double>(queries);
  std::printf("  %-24s %10.1f %14.0f %14.0f\n", name, 1e3 * r.build_s, n / r.one_thread_s, n / r.two_threads_s);
}

}  // namespace

int main() {
  const conform::Mesh mesh = tube_mesh();
  const std::vector<Eigen::Vector3d> queries = queries_near(mesh, 1000000, 17);
  std::printf("closest point on a mesh: %zu triangles, %zu queries within +-2 mm of the surface\n", mesh.faces.size(),
              queries.size());
  std::printf("  %-24s %10s %14s %14s\n", "", "build [ms]", "queries/s x1", "queries/s x2");

  std::vector<double> conform_d2(queries.size()), vtk_d2(queries.size());
  Row conform_row;
  conform_row.build_s = best_seconds(2, [&] { conform::TriangleIndex index(mesh); });
  const conform::TriangleIndex index(mesh);
  const auto conform_slice = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) conform_d2[i] = index.closest(queries[i]).sq_distance;
  };
  conform_row.one_thread_s = best_seconds(2, [&] { parallel_for(queries.size(), 1, conform_slice); });
  conform_row.two_threads_s = best_seconds(2, [&] { parallel_for(queries.size(), 2, conform_slice); });
  print_row("conform::TriangleIndex", conform_row, queries.size());

  const vtkSmartPointer<vtkPolyData> poly = to_vtk(mesh);
  Row vtk_row;
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(poly);
  vtk_row.build_s = best_seconds(2, [&] {
    locator->FreeSearchStructure();
    locator->BuildLocator();
  });
  const auto vtk_slice = [&](std::size_t begin, std::size_t end) {
    vtkNew<vtkGenericCell> cell;
    double closest[3];
    vtkIdType cell_id = 0;
    int sub_id = 0;
    for (std::size_t i = begin; i < end; ++i) {
      locator->FindClosestPoint(queries[i].data(), closest, cell, cell_id, sub_id, vtk_d2[i]);
    }
  };
  vtk_row.one_thread_s = best_seconds(2, [&] { parallel_for(queries.size(), 1, vtk_slice); });
  vtk_row.two_threads_s = best_seconds(2, [&] { parallel_for(queries.size(), 2, vtk_slice); });
  print_row("vtkStaticCellLocator", vtk_row, queries.size());

  std::printf("  ratio VTK / conform: build %.2f, queries x1 %.2f, x2 %.2f\n", vtk_row.build_s / conform_row.build_s,
              vtk_row.one_thread_s / conform_row.one_thread_s, vtk_row.two_threads_s / conform_row.two_threads_s);
  double largest = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    largest = std::max(largest, std::abs(std::sqrt(conform_d2[i]) - std::sqrt(vtk_d2[i])));
  }
  std::printf("  largest |distance conform - distance VTK| over all queries: %.3g mm\n", largest);
  return 0;
}
