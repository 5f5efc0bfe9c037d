// Loading a 2-million-triangle mesh: conform::read_mesh against PCL's readers in the same run, best of 3.
// The mesh is a 1000 x 1000 grid of quads (2,000,000 triangles, 1,002,001 vertices) on a wavy surface, written by
// conform as binary STL (100 MB) and binary little-endian PLY (38 MB) to a temporary directory. Peers:
//   STL: pcl::io::loadPolygonFileSTL (VTK's vtkSTLReader, which also merges coincident corners)
//   PLY: pcl::io::loadPolygonFilePLY (VTK's vtkPLYReader) and pcl::io::loadPLYFile (PCL's own PLYReader)
// All readers end in their own mesh type (conform::Mesh with double vertices; pcl::PolygonMesh). Ratios > 1 mean the
// peer is slower. The requirement is conform < 2 s for each format on the 2-core CI machine.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <pcl/PolygonMesh.h>
#include <pcl/io/ply_io.h>
#include <pcl/io/vtk_lib_io.h>
#include <unistd.h>

#include "bench_timer.h"
#include "conform/core/io.h"

namespace {

using conform::bench::best_seconds;

constexpr int kRepeats = 3;
constexpr int kQuads = 1000;  // per side

conform::Mesh grid_mesh(int n) {
  conform::Mesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>(n + 1));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = 0.5 * i;
      const double y = 0.5 * j;
      mesh.vertices.emplace_back(x, y, 10.0 * std::sin(0.01 * x) * std::cos(0.013 * y));
    }
  }
  const auto at = [n](int i, int j) { return static_cast<std::int32_t>(j * (n + 1) + i); };
  mesh.faces.reserve(2 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

std::string make_temp_dir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "conform-io-bench-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    std::perror("mkdtemp");
    std::exit(1);
  }
  return pattern;
}

void row(const char* what, double conform_s, const char* peer, double peer_s, std::size_t peer_faces) {
  std::printf("%-5s conform %6.3f s | %-34s %6.3f s (%zu triangles) | ratio %5.2f\n", what, conform_s, peer, peer_s,
              peer_faces, peer_s / conform_s);
}

}  // namespace

int main() {
  const std::string dir = make_temp_dir();
  const std::string stl = dir + "/grid.stl";
  const std::string ply = dir + "/grid.ply";
  const conform::Mesh mesh = grid_mesh(kQuads);
  conform::write_mesh(stl, mesh);
  conform::write_mesh(ply, mesh);
  std::printf("mesh: %zu vertices, %zu triangles; STL %.1f MB, PLY %.1f MB; best of %d\n", mesh.vertices.size(),
              mesh.faces.size(), static_cast<double>(std::filesystem::file_size(stl)) / 1e6,
              static_cast<double>(std::filesystem::file_size(ply)) / 1e6, kRepeats);

  std::size_t faces = 0;
  std::size_t vertices = 0;
  const double stl_s = best_seconds(kRepeats, [&] {
    const conform::Mesh m = conform::read_mesh(stl);
    faces = m.faces.size();
    vertices = m.vertices.size();
  });
  std::printf("conform STL read: %zu vertices, %zu triangles\n", vertices, faces);
  const double ply_s = best_seconds(kRepeats, [&] { faces = conform::read_mesh(ply).faces.size(); });

  // A fresh PolygonMesh each time: PCL's PLYReader appends to the polygons already there.
  std::size_t peer_faces = 0;
  const double vtk_stl_s = best_seconds(kRepeats, [&] {
    pcl::PolygonMesh peer;
    pcl::io::loadPolygonFileSTL(stl, peer);
    peer_faces = peer.polygons.size();
  });
  row("STL", stl_s, "pcl::io::loadPolygonFileSTL (VTK)", vtk_stl_s, peer_faces);
  const double vtk_ply_s = best_seconds(kRepeats, [&] {
    pcl::PolygonMesh peer;
    pcl::io::loadPolygonFilePLY(ply, peer);
    peer_faces = peer.polygons.size();
  });
  row("PLY", ply_s, "pcl::io::loadPolygonFilePLY (VTK)", vtk_ply_s, peer_faces);
  const double pcl_ply_s = best_seconds(kRepeats, [&] {
    pcl::PolygonMesh peer;
    pcl::io::loadPLYFile(ply, peer);
    peer_faces = peer.polygons.size();
  });
  row("PLY", ply_s, "pcl::io::loadPLYFile (PCL's own)", pcl_ply_s, peer_faces);

  std::filesystem::remove_all(dir);
  const bool ok = stl_s < 2.0 && ply_s < 2.0;
  std::printf("requirement (< 2 s each): %s\n", ok ? "met" : "NOT met");
  return ok ? 0 : 1;
}
