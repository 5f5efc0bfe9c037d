#include "vertex_welder.h"

#include <cstring>
#include <limits>

#include "conform/core/error.h"

namespace conform::detail {

namespace {

std::uint32_t bits_of(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits == 0x80000000u ? 0u : bits;  // -0.0 welds with 0.0
}

// A multiply-xorshift mix (the finaliser of MurmurHash3) over the three coordinates' bits: neighbouring grid
// coordinates differ in low mantissa bits, which must spread over the whole table.
std::uint64_t hash_of(const std::array<std::uint32_t, 3>& key) {
  std::uint64_t h = (std::uint64_t{key[0]} << 32 | key[1]) * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 32) ^ (std::uint64_t{key[2]} * 0xC2B2AE3D27D4EB4Full);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  return h;
}

constexpr std::uint64_t kIndexMask = 0xFFFFFFFFull;

}  // namespace

VertexWelder::VertexWelder(const std::string& path, std::size_t expected_vertices) : path_(path) {
  std::size_t capacity = 1024;
  while (capacity < 2 * expected_vertices) capacity *= 2;
  slots_.assign(capacity, 0);
  mask_ = capacity - 1;
  keys_.reserve(expected_vertices);
}

std::size_t VertexWelder::find_slot(const Key& key, std::uint64_t hash) const {
  const std::uint64_t tag = hash & ~kIndexMask;
  std::size_t slot = static_cast<std::size_t>(hash) & mask_;
  while (true) {
    const std::uint64_t entry = slots_[slot];
    if (entry == 0) return slot;
    if ((entry & ~kIndexMask) == tag && keys_[(entry & kIndexMask) - 1] == key) return slot;
    slot = (slot + 1) & mask_;
  }
}

std::int32_t VertexWelder::add(float x, float y, float z) {
  const Key key = {bits_of(x), bits_of(y), bits_of(z)};
  const std::uint64_t hash = hash_of(key);
  std::size_t slot = find_slot(key, hash);
  if (slots_[slot] != 0) return static_cast<std::int32_t>((slots_[slot] & kIndexMask) - 1);
  if (keys_.size() >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw Error(path_ + ": more distinct vertices than 32-bit face indices can address");
  }
  if (2 * (keys_.size() + 1) > slots_.size()) {
    grow();
    slot = find_slot(key, hash);
  }
  keys_.push_back(key);
  slots_[slot] = (hash & ~kIndexMask) | keys_.size();
  return static_cast<std::int32_t>(keys_.size() - 1);
}

void VertexWelder::grow() {
  std::vector<std::uint64_t> old;
  old.swap(slots_);
  slots_.assign(old.size() * 2, 0);
  mask_ = slots_.size() - 1;
  for (std::uint64_t entry : old) {
    if (entry == 0) continue;
    std::size_t slot = static_cast<std::size_t>(hash_of(keys_[(entry & kIndexMask) - 1])) & mask_;
    while (slots_[slot] != 0) slot = (slot + 1) & mask_;
    slots_[slot] = entry;
  }
}

std::vector<Eigen::Vector3d> VertexWelder::vertices() const {
  std::vector<Eigen::Vector3d> out(keys_.size());
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    float xyz[3];
    std::memcpy(xyz, keys_[i].data(), sizeof(xyz));
    out[i] = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  }
  return out;
}

}  // namespace conform::detail
