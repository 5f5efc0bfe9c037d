#pragma once
// Merging the bit-identical corners of an STL's triangles into shared vertices. An open-addressing table (linear
// probing, power-of-two size, load <= 1/2) rather than std::unordered_map: one flat array without a node per entry,
// which matters at the 6 million lookups of a 2-million-triangle scan (several times faster than unordered_map).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform::detail {

class VertexWelder {
 public:
  // `path` names the file in the error thrown when the vertices outgrow 32-bit face indices.
  VertexWelder(const std::string& path, std::size_t expected_vertices);

  // The index of the vertex with exactly these coordinates, a new one if they were not seen before.
  // -0.0 and 0.0 are the same vertex; NaNs with the same bits are one vertex (the NonFinitePolicy deals with it).
  std::int32_t add(float x, float y, float z);

  std::size_t size() const { return keys_.size(); }
  std::vector<Eigen::Vector3d> vertices() const;

 private:
  using Key = std::array<std::uint32_t, 3>;
  void grow();
  std::size_t find_slot(const Key& key, std::uint64_t hash) const;

  const std::string& path_;
  std::vector<Key> keys_;             // the distinct vertices' bits, in order of first appearance
  std::vector<std::uint64_t> slots_;  // (hash >> 32) << 32 | (index + 1); 0 is an empty slot
  std::size_t mask_ = 0;
};

}  // namespace conform::detail
