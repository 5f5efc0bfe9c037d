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

constexpr std::size_t kFaceBytes = 3 * 4 + 2 * 8 + 13 * 8;

bool take_face(Reader& in, conform_cad_face* f) {
  std::int32_t surface = 0, reversed = 0, sense = 0;
  std::uint64_t body = 0, triangles = 0;
  bool ok = in.take(&surface) && in.take(&reversed) && in.take(&sense) && in.take(&body) && in.take(&triangles) &&
            in.take(&f->area_mm2);
  for (double* v : {f->centre_mm, f->origin_mm, f->axis}) {
    for (int k = 0; k < 3; ++k) ok = ok && in.take(&v[k]);
  }
  ok = ok && in.take(&f->radius_mm) && in.take(&f->minor_radius_mm) && in.take(&f->half_angle_rad);
  f->surface = surface;
  f->reversed = reversed;
  f->sense = sense;
  f->body = body;
  f->triangles = triangles;
  return ok;
}

// Why the face record cannot be right, or empty.
std::string face_problem(const conform_cad_face& f, std::size_t bodies) {
  if (f.surface < CONFORM_CAD_PLANE || f.surface > CONFORM_CAD_OTHER_SURFACE) {
    return "an unknown surface type " + std::to_string(f.surface);
  }
  if ((f.reversed != 0 && f.reversed != 1) || f.sense < -1 || f.sense > 1) return "an orientation out of range";
  if (f.body >= bodies) return "body " + std::to_string(f.body) + " of " + std::to_string(bodies);
  const double numbers[] = {f.area_mm2, f.radius_mm, f.minor_radius_mm, f.half_angle_rad};
  for (const double x : numbers) {
    if (!std::isfinite(x)) return "a number that is not finite";
  }
  if (!finite3(f.centre_mm) || !finite3(f.origin_mm) || !finite3(f.axis)) return "a point that is not finite";
  if (f.area_mm2 < 0.0) return "a negative area";
  if (f.surface > CONFORM_CAD_TORUS) return "";
  const double norm = std::sqrt(f.axis[0] * f.axis[0] + f.axis[1] * f.axis[1] + f.axis[2] * f.axis[2]);
  if (std::abs(norm - 1.0) > 1e-6) return "an axis that is not a unit vector";
  if (f.sense == 0) return "an analytic surface without an outside";
  const bool round = f.surface == CONFORM_CAD_CYLINDER || f.surface == CONFORM_CAD_SPHERE ||
                     f.surface == CONFORM_CAD_TORUS;
  if (round && !(f.radius_mm > 0.0)) return "a radius that is not > 0";
  if (f.surface == CONFORM_CAD_TORUS && !(f.minor_radius_mm > 0.0)) return "a minor radius that is not > 0";
  if (f.surface == CONFORM_CAD_CONE && !(f.half_angle_rad > 0.0 && f.half_angle_rad < 1.5707963267948966)) {
    return "a cone angle out of (0, 90) deg";
  }
  return "";
}

// The faces section after the warnings (the triangles' faces and the face records), checked against the mesh and
// the bodies already decoded.
bool decode_faces(Reader& in, CadWireResult* out, std::string* why) {
  std::uint64_t count = 0, face_count = 0;
  if (!in.take(&count)) return fail(why, "a truncated count of triangle faces");
  if (count != out->mesh.faces.size()) return fail(why, "triangle faces for other than every triangle");
  const char* at = in.take_array(count, sizeof(std::int32_t));
  if (at == nullptr) return fail(why, "more triangle faces than bytes");
  out->triangle_faces.resize(count);
  if (count > 0) std::memcpy(out->triangle_faces.data(), at, count * sizeof(std::int32_t));
  if (!in.take(&face_count)) return fail(why, "a truncated face count");
  if (face_count > in.left() / kFaceBytes) return fail(why, "more faces than bytes");
  std::uint64_t body_faces = 0;
  for (const conform_cad_body& b : out->bodies) body_faces += b.faces;
  if (face_count != body_faces) return fail(why, "faces that do not add up to the bodies' faces");
  out->faces.resize(face_count);
  std::vector<std::uint64_t> per_body(out->bodies.size(), 0), failed(out->bodies.size(), 0),
      triangles(out->bodies.size(), 0);
  for (std::size_t i = 0; i < face_count; ++i) {
    conform_cad_face& f = out->faces[i];
    if (!take_face(in, &f)) return fail(why, "a truncated face");
    const std::string problem = face_problem(f, out->bodies.size());
    if (!problem.empty()) return fail(why, "face " + std::to_string(i + 1) + " with " + problem);
    ++per_body[f.body];
    failed[f.body] += f.triangles == 0 ? 1 : 0;
    triangles[f.body] += f.triangles;
  }
  for (std::size_t b = 0; b < out->bodies.size(); ++b) {
    const conform_cad_body& body = out->bodies[b];
    if (per_body[b] != body.faces || failed[b] != body.failed_faces || triangles[b] != body.triangles) {
      return fail(why, "body " + std::to_string(b + 1) + " whose faces do not add up");
    }
  }
  std::vector<std::uint64_t> seen(face_count, 0);
  for (std::size_t t = 0; t < count; ++t) {
    const std::int32_t face = out->triangle_faces[t];
    if (face < 0 || static_cast<std::uint64_t>(face) >= face_count) {
      return fail(why, "triangle " + std::to_string(t) + " of face " + std::to_string(face) + " of " +
                           std::to_string(face_count));
    }
    ++seen[static_cast<std::size_t>(face)];
  }
  for (std::size_t i = 0; i < face_count; ++i) {
    if (seen[i] != out->faces[i].triangles) {
      return fail(why, "face " + std::to_string(i + 1) + " whose triangles do not match its count");
    }
  }
  return true;
}

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
  const std::size_t triangle_faces = r.triangle_faces != nullptr ? r.triangle_count : 0;
  put(p, static_cast<std::uint64_t>(triangle_faces));
  p.append(reinterpret_cast<const char*>(r.triangle_faces), triangle_faces * sizeof(std::int32_t));
  put(p, static_cast<std::uint64_t>(r.face_count));
  for (std::size_t i = 0; i < r.face_count; ++i) {
    const conform_cad_face& f = r.faces[i];
    put(p, static_cast<std::int32_t>(f.surface));
    put(p, static_cast<std::int32_t>(f.reversed));
    put(p, static_cast<std::int32_t>(f.sense));
    put(p, static_cast<std::uint64_t>(f.body));
    put(p, static_cast<std::uint64_t>(f.triangles));
    put(p, f.area_mm2);
    for (const double* v : {f.centre_mm, f.origin_mm, f.axis}) {
      for (int k = 0; k < 3; ++k) put(p, v[k]);
    }
    put(p, f.radius_mm);
    put(p, f.minor_radius_mm);
    put(p, f.half_angle_rad);
  }
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
  if (!decode_faces(in, out, why)) return false;
  if (in.left() != 0) return fail(why, std::to_string(in.left()) + " bytes after the end");
  return true;
}

}  // namespace conform::detail
