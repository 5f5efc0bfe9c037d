#pragma once
// Meshes, clouds and checks shared by the io_*_test.cpp files.

#include <cmath>
#include <cstddef>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/cloud.h"
#include "conform/core/error.h"
#include "conform/core/mesh.h"

namespace conform::test {

// A wavy nx-by-ny grid of quads split into triangles, with coordinates that are not floats (so that float formats
// visibly round them) and, optionally, unit normals.
inline Mesh grid_mesh(int nx, int ny, bool normals, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  Mesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.vertices.emplace_back(0.1 * i + jitter(rng), 0.3 * j + jitter(rng), std::sin(0.7 * i) * 1e3 / 3.0);
      if (normals) mesh.normals.push_back(Eigen::Vector3d(jitter(rng), jitter(rng), 1.0).normalized());
    }
  }
  const auto at = [nx](int i, int j) { return static_cast<std::int32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

inline Cloud random_cloud(std::size_t n, bool normals, unsigned seed = 11) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coordinate(-500.0f, 500.0f);
  Cloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.push_back({coordinate(rng), coordinate(rng), coordinate(rng) * 1e-3f});
    if (normals) {
      const Eigen::Vector3f v = Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
      cloud.normals.push_back(pcl::Normal(v.x(), v.y(), v.z()));
    }
  }
  return cloud;
}

// Through a volatile float: GCC 12.2's SLP vectorizer (-O2 and up, x86-64) turns a pair of (double)(float)x
// conversions into a plain copy, so the rounding written the obvious way does not happen in a Release build.
inline double as_float(double x) {
  volatile float rounded = static_cast<float>(x);
  return rounded;
}
inline Eigen::Vector3d as_float(const Eigen::Vector3d& v) {
  return {as_float(v.x()), as_float(v.y()), as_float(v.z())};
}

// How a format stores coordinates, and so what reading back must give (tolerance: none in every case):
enum class Stored {
  kDouble,     // the doubles themselves
  kFloat,      // binary floats: exactly the doubles rounded to float
  kFloatText,  // the shortest text of those floats: read as doubles, they round to the same floats
};

inline Eigen::Vector3d stored_as(const Eigen::Vector3d& v, Stored stored) {
  return stored == Stored::kDouble ? v : as_float(v);
}

inline void expect_same_mesh(const Mesh& got, const Mesh& want, Stored stored) {
  ASSERT_EQ(got.vertices.size(), want.vertices.size());
  ASSERT_EQ(got.normals.size(), want.normals.size());
  ASSERT_EQ(got.faces.size(), want.faces.size());
  // kFloatText compares after rounding what was read; kFloat must match without that.
  const Stored got_as = stored == Stored::kFloatText ? Stored::kFloat : Stored::kDouble;
  for (std::size_t i = 0; i < want.vertices.size(); ++i) {
    ASSERT_EQ(stored_as(got.vertices[i], got_as), stored_as(want.vertices[i], stored)) << "vertex " << i;
  }
  for (std::size_t i = 0; i < want.normals.size(); ++i) {
    ASSERT_EQ(stored_as(got.normals[i], got_as), stored_as(want.normals[i], stored)) << "normal " << i;
  }
  for (std::size_t f = 0; f < want.faces.size(); ++f) ASSERT_EQ(got.faces[f], want.faces[f]) << "face " << f;
}

inline void expect_same_cloud(const Cloud& got, const Cloud& want) {
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.normals.size(), want.normals.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got.points[i].getVector3fMap(), want.points[i].getVector3fMap()) << "point " << i;
  }
  for (std::size_t i = 0; i < want.normals.size(); ++i) {
    ASSERT_EQ(got.normals[i].getNormalVector3fMap(), want.normals[i].getNormalVector3fMap()) << "normal " << i;
  }
}

// The message of the conform::Error that `fn` throws; a test failure (and "") when it throws none.
template <typename Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no conform::Error thrown";
  return "";
}

}  // namespace conform::test

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "'" << (text) << "' lacks '" << (part) << "'"
