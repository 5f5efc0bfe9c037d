#include "cad_wire.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace conform::detail {

namespace {

std::string message(char kind, const std::string& payload) {
  std::string out(kCadWireHeader, '\0');
  out[0] = kind;
  const auto size = static_cast<std::uint64_t>(payload.size());
  std::memcpy(&out[1], &size, sizeof size);
  return out + payload;
}

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void put_text(std::string& out, const char* text, std::size_t size) {
  put(out, static_cast<std::uint32_t>(size));
  out.append(text, size);
}

// Reads from an untrusted payload: every take fails, rather than reading past the end, once the bytes run out.
class Reader {
 public:
  Reader(const char* data, std::size_t size) : data_(data), left_(size) {}
  template <class T>
  bool take(T* value) {
    if (left_ < sizeof(T)) return false;
    std::memcpy(value, data_, sizeof(T));
    data_ += sizeof(T);
    left_ -= sizeof(T);
    return true;
  }
  // `count` elements of `element_size` bytes: false when they do not fit in what is left (no overflow: divides).
  const char* take_array(std::size_t count, std::size_t element_size) {
    if (count > left_ / element_size) return nullptr;
    const char* at = data_;
    data_ += count * element_size;
    left_ -= count * element_size;
    return at;
  }
  bool take_text(std::string* text) {
    std::uint32_t size = 0;
    if (!take(&size)) return false;
    const char* at = take_array(size, 1);
    if (at == nullptr) return false;
    text->assign(at, size);
    return true;
  }
  std::size_t left() const { return left_; }

 private:
  const char* data_;
  std::size_t left_;
};

bool fail(std::string* why, const std::string& text) {
  *why = text;
  return false;
}

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

}  // namespace

std::string cad_progress_message(const char* stage, double fraction) {
  std::string payload;
  put(payload, fraction);
  payload += stage;
  return message('P', payload);
}

std::string cad_error_message(CadChildError category, const std::string& text) {
  std::string payload(1, static_cast<char>(category));
  return message('E', payload + text);
}

std::string cad_result_message(const conform_cad_result& r) {
  std::string p;
  const std::size_t bytes = 64 + r.vertex_count * 24 + r.triangle_count * 12 + r.body_count * 100;
  p.reserve(bytes);
  put_text(p, r.file_unit, strnlen(r.file_unit, sizeof r.file_unit));
  put(p, r.mm_per_file_unit);
  put(p, static_cast<std::uint64_t>(r.vertex_count));
  p.append(reinterpret_cast<const char*>(r.vertices), r.vertex_count * 3 * sizeof(double));
  put(p, static_cast<std::uint64_t>(r.triangle_count));
  p.append(reinterpret_cast<const char*>(r.triangles), r.triangle_count * 3 * sizeof(std::int32_t));
  put(p, static_cast<std::uint64_t>(r.body_count));
  for (std::size_t i = 0; i < r.body_count; ++i) {
    const conform_cad_body& b = r.bodies[i];
    put(p, static_cast<std::int32_t>(b.kind));
    put(p, static_cast<std::uint64_t>(b.faces));
    put(p, static_cast<std::uint64_t>(b.triangles));
    put(p, static_cast<std::uint64_t>(b.failed_faces));
    for (int k = 0; k < 3; ++k) put(p, b.box_min_mm[k]);
    for (int k = 0; k < 3; ++k) put(p, b.box_max_mm[k]);
    put(p, b.volume_mm3);
    put(p, static_cast<std::int32_t>(b.flipped));
  }
  const char* warnings = r.warnings != nullptr ? r.warnings : "";
  put_text(p, warnings, std::strlen(warnings));
  return message('R', p);
}

bool decode_cad_result(const char* payload, std::size_t size, std::size_t max_triangles, CadWireResult* out,
                       std::string* why) {
  Reader in(payload, size);
  std::uint64_t vertex_count = 0, triangle_count = 0, body_count = 0;
  if (!in.take_text(&out->file_unit) || !in.take(&out->mm_per_file_unit) || !in.take(&vertex_count)) {
    return fail(why, "a truncated header");
  }
  if (!(std::isfinite(out->mm_per_file_unit) && out->mm_per_file_unit > 0.0)) {
    return fail(why, "a unit factor that is not a positive number");
  }
  const char* vertices = in.take_array(vertex_count, 3 * sizeof(double));
  if (vertices == nullptr) return fail(why, "more vertices than bytes");
  if (vertex_count > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max())) {
    return fail(why, "more vertices than a 32-bit index reaches");
  }
  out->mesh.vertices.resize(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    double v[3];
    std::memcpy(v, vertices + i * sizeof v, sizeof v);
    if (!finite3(v)) return fail(why, "vertex " + std::to_string(i) + " is not finite");
    out->mesh.vertices[i] = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  if (!in.take(&triangle_count)) return fail(why, "a truncated triangle count");
  if (triangle_count > max_triangles) {
    return fail(why,
                std::to_string(triangle_count) + " triangles, over the budget of " + std::to_string(max_triangles));
  }
  const char* triangles = in.take_array(triangle_count, 3 * sizeof(std::int32_t));
  if (triangles == nullptr) return fail(why, "more triangles than bytes");
  out->mesh.faces.resize(triangle_count);
  for (std::size_t i = 0; i < triangle_count; ++i) {
    std::int32_t t[3];
    std::memcpy(t, triangles + i * sizeof t, sizeof t);
    for (const std::int32_t index : t) {
      if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count) {
        return fail(why, "triangle " + std::to_string(i) + " has vertex index " + std::to_string(index) + " of " +
                             std::to_string(vertex_count));
      }
    }
    out->mesh.faces[i] = {t[0], t[1], t[2]};
  }
  if (!in.take(&body_count)) return fail(why, "a truncated body count");
  constexpr std::size_t kBodyBytes = 4 + 3 * 8 + 7 * 8 + 4;
  if (body_count > in.left() / kBodyBytes) return fail(why, "more bodies than bytes");
  std::uint64_t body_triangles = 0;
  for (std::size_t i = 0; i < body_count; ++i) {
    conform_cad_body b{};
    std::int32_t kind = 0, flipped = 0;
    std::uint64_t faces = 0, tris = 0, failed = 0;
    bool ok = in.take(&kind) && in.take(&faces) && in.take(&tris) && in.take(&failed);
    for (int k = 0; k < 3; ++k) ok = ok && in.take(&b.box_min_mm[k]);
    for (int k = 0; k < 3; ++k) ok = ok && in.take(&b.box_max_mm[k]);
    ok = ok && in.take(&b.volume_mm3) && in.take(&flipped);
    if (!ok) return fail(why, "a truncated body");
    if (kind != CONFORM_CAD_SOLID && kind != CONFORM_CAD_OPEN_SHELL && kind != CONFORM_CAD_FREE_FACES) {
      return fail(why, "body " + std::to_string(i + 1) + " of unknown kind " + std::to_string(kind));
    }
    if (failed > faces || tris > triangle_count || !std::isfinite(b.volume_mm3)) {
      return fail(why, "body " + std::to_string(i + 1) + " with inconsistent counts");
    }
    b.kind = kind;
    b.faces = faces;
    b.triangles = tris;
    b.failed_faces = failed;
    b.flipped = flipped != 0 ? 1 : 0;
    body_triangles += tris;
    out->bodies.push_back(b);
  }
  if (body_triangles != triangle_count) return fail(why, "bodies whose triangles do not add up to the total");
  if (!in.take_text(&out->warnings)) return fail(why, "truncated warnings");
  if (in.left() != 0) return fail(why, std::to_string(in.left()) + " bytes after the end");
  return true;
}

}  // namespace conform::detail
