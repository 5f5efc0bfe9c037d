// Welding a triangle soup back into the shared-vertex mesh it came from.

#include "conform/core/mesh_weld.h"

#include <gtest/gtest.h>

namespace conform {
namespace {

Mesh grid(int n) {
  Mesh mesh;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) mesh.vertices.emplace_back(1000.0 + 3.7 * i, -20.0 + 2.9 * j, 0.1 * i * j);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j;
      mesh.faces.push_back({a, a + n + 1, a + 1});
      mesh.faces.push_back({a + 1, a + n + 1, a + n + 2});
    }
  return mesh;
}

TEST(MeshWeld, ASoupWeldsBackToTheSharedVertexMesh) {
  const Mesh shared = grid(6);
  Mesh soup;
  for (const Face& f : shared.faces) {
    const auto base = static_cast<std::int32_t>(soup.vertices.size());
    for (const std::int32_t v : f) soup.vertices.push_back(shared.vertices[static_cast<std::size_t>(v)]);
    soup.faces.push_back({base, base + 1, base + 2});
  }
  const MeshWeldResult r = weld_coincident_vertices(soup, "soup");
  EXPECT_EQ(r.mesh.vertices.size(), shared.vertices.size());
  EXPECT_EQ(r.merged_vertices, soup.vertices.size() - shared.vertices.size());
  EXPECT_EQ(r.dropped_faces, 0u);
  ASSERT_EQ(r.mesh.faces.size(), shared.faces.size());
  for (std::size_t f = 0; f < shared.faces.size(); ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(r.mesh.vertices[static_cast<std::size_t>(r.mesh.faces[f][k])],
                shared.vertices[static_cast<std::size_t>(shared.faces[f][k])]);
    }
  }
}

TEST(MeshWeld, AWeldedMeshIsUnchangedAndCollapsedFacesAreDropped) {
  const Mesh shared = grid(3);
  const MeshWeldResult same = weld_coincident_vertices(shared, "grid");
  EXPECT_EQ(same.merged_vertices, 0u);
  EXPECT_EQ(same.mesh.vertices, shared.vertices);
  EXPECT_EQ(same.mesh.faces, shared.faces);
  Mesh sliver = shared;
  sliver.vertices[1] = sliver.vertices[0];  // two corners of face 0 at one place
  const MeshWeldResult r = weld_coincident_vertices(sliver, "sliver");
  EXPECT_EQ(r.merged_vertices, 1u);
  EXPECT_EQ(r.dropped_faces, 1u);
}

}  // namespace
}  // namespace conform
