#include "inputs.h"

#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <limits>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>

#include <pybind11/numpy.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/transform_io.h"

namespace conform::python {
namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

std::vector<Eigen::Vector3d> rows_of(const py::handle& value, const std::string& what) {
  const Rows a = Rows::ensure(value);
  if (!a) throw Error(what + ": not a path, a conform.Geometry or a numeric array");
  if (a.ndim() != 2 || a.shape(1) != 3) throw Error(what + ": expected an (N, 3) array, got shape " + shape_text(a));
  std::vector<Eigen::Vector3d> rows(static_cast<std::size_t>(a.shape(0)));
  const double* data = a.data();
  for (std::size_t i = 0; i < rows.size(); ++i)
    rows[i] = Eigen::Vector3d(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  return rows;
}

// One face index as the user gave it, for messages: 3.5, -1, 4294967296.
template <class T>
std::string index_text(T v) {
  if constexpr (std::is_floating_point_v<T>) {
    std::ostringstream text;
    text.precision(17);
    text << v;
    return text.str();
  } else {
    return std::to_string(v);
  }
}

// Faces as integers in [0, vertices) or conform.Error naming the argument, the face and the value: a cast would
// truncate 3.5 to 3 and wrap 2^32 to 0, a valid index to the wrong vertex.
template <class T>
std::vector<Face> checked_faces(const py::array& faces, std::size_t vertices, const std::string& what) {
  using Typed = py::array_t<T, py::array::c_style | py::array::forcecast>;
  const Typed a = Typed::ensure(faces);
  if (!a) throw Error(what + ": faces must be an (F, 3) integer array");
  const T* data = a.data();
  const auto limit = static_cast<long double>(vertices);
  std::vector<Face> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < 3 * out.size(); ++i) {
    const T v = data[i];
    const auto fail = [&](const std::string& why) {
      throw Error(what + " faces[" + std::to_string(i / 3) + ", " + std::to_string(i % 3) + "] = " + index_text(v) +
                  ": " + why);
    };
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v) || std::trunc(v) != v) fail("not an integer index");
    }
    if constexpr (std::is_signed_v<T>) {
      if (v < 0) fail("a negative vertex index");
    }
    if (static_cast<long double>(v) > std::numeric_limits<std::int32_t>::max()) {
      fail("above the largest index (2^31 - 1)");
    }
    if (static_cast<long double>(v) >= limit) fail("not below the vertex count " + std::to_string(vertices));
    out[i / 3][i % 3] = static_cast<std::int32_t>(v);
  }
  return out;
}

std::vector<Face> faces_of(const py::handle& value, std::size_t vertices, const std::string& what) {
  const py::array a = py::module_::import("numpy").attr("asarray")(value);
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw Error(what + ": faces must be an (F, 3) integer array, got shape " + shape_text(a));
  }
  switch (a.dtype().kind()) {
    case 'i':
      return checked_faces<std::int64_t>(a, vertices, what);
    case 'u':
      return checked_faces<std::uint64_t>(a, vertices, what);
    case 'f':
      return checked_faces<double>(a, vertices, what);
    default:
      throw Error(what + ": faces must be an (F, 3) integer array, got dtype " +
                  py::str(a.dtype()).cast<std::string>());
  }
}

bool is_path(const py::handle& value) { return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"); }

}  // namespace

std::string path_of(const py::handle& value) {
  if (value.is_none()) return "";
  if (!is_path(value)) throw Error("expected a path (str or os.PathLike)");
  return py::str(py::module_::import("os").attr("fspath")(value)).cast<std::string>();
}

std::string for_python(const std::string& message) {
  static const std::regex temporary(R"(\S*/conform-py-[A-Za-z0-9]{6}/(\w+)\.(ply|txt))");
  static const std::regex flag(R"(--([a-z][a-z0-9]*(-[a-z0-9]+)*))");
  const std::string text = std::regex_replace(message, temporary, "the $1 argument (given in memory)");
  std::string out;
  std::size_t done = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), flag); it != std::sregex_iterator(); ++it) {
    const std::size_t at = static_cast<std::size_t>(it->position(0));
    // A flag starts a word: "--cad-deflection", not the middle of "a--b".
    if (at > 0 && !std::isspace(static_cast<unsigned char>(text[at - 1])) &&
        std::string("('\"").find(text[at - 1]) == std::string::npos) {
      continue;
    }
    std::string name = (*it)[1].str();
    std::replace(name.begin(), name.end(), '-', '_');
    out += text.substr(done, at - done) + name;
    done = at + static_cast<std::size_t>(it->length(0));
  }
  return out + text.substr(done);
}

void set_cad_options(const py::handle& deflection, const py::handle& angle_deg, const py::handle& save_mesh,
                     CadReadOptions& cad) {
  if (!deflection.is_none()) {
    const double mm = deflection.cast<double>();
    if (!(mm > 0.0) || !std::isfinite(mm)) {
      throw Error("cad_deflection: the tessellation's chordal deflection must be a finite number of mm above 0, got " +
                  std::string(py::str(deflection)));
    }
    cad.deflection_mm = mm;
  }
  if (!angle_deg.is_none()) {
    const double deg = angle_deg.cast<double>();
    if (!(deg > 0.0 && deg <= 90.0)) {
      throw Error("cad_angle_deg: the angular deflection must be in (0, 90] deg, got " +
                  std::string(py::str(angle_deg)));
    }
    cad.angular_deflection_rad = deg * M_PI / 180.0;
  }
  cad.save_mesh_path = path_of(save_mesh);
}

Inputs::~Inputs() {
  if (directory_.empty()) return;
  std::error_code ignored;
  std::filesystem::remove_all(directory_, ignored);
}

std::string Inputs::temporary(const std::string& name) {
  if (directory_.empty()) {
    std::string pattern = (std::filesystem::temp_directory_path() / "conform-py-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw Error("cannot create a temporary directory in " + pattern);
    directory_ = pattern;
  }
  written_.push_back((std::filesystem::path(directory_) / name).string());
  return written_.back();
}

bool Inputs::in_memory(const std::string& path) const {
  return std::find(written_.begin(), written_.end(), path) != written_.end();
}

std::string Inputs::geometry(const py::handle& value, const char* what) {
  if (value.is_none()) return "";
  if (is_path(value)) return path_of(value);
  WriteOptions exact;
  exact.double_precision = true;
  const std::string path = temporary(std::string(what) + ".ply");
  if (py::isinstance<Geometry>(value)) {
    write_mesh(path, value.cast<const Geometry&>().mesh, exact);
    return path;
  }
  Mesh mesh;
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    const py::sequence pair = value.cast<py::sequence>();
    if (pair.size() != 2) throw Error(std::string(what) + ": give (vertices, faces), an (N, 3) array or a path");
    mesh.vertices = rows_of(pair[0], std::string(what) + " vertices");
    mesh.faces = faces_of(pair[1], mesh.vertices.size(), std::string(what));
  } else {
    mesh.vertices = rows_of(value, what);
  }
  check_consistent(mesh, what);
  write_mesh(path, mesh, exact);
  return path;
}

std::string Inputs::transform(const py::handle& value, const char* what) {
  if (value.is_none()) return "";
  if (is_path(value)) return path_of(value);
  const Rows a = Rows::ensure(value);
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw Error(std::string(what) + ": expected a path or a (4, 4) array");
  }
  Eigen::Isometry3d T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = a.at(r, c);
  }
  const std::string path = temporary(std::string(what) + ".txt");
  write_transform(path, T);
  return path;
}

struct Progress::State {
  py::object callback;
  std::mutex mutex;
  std::exception_ptr error;
};

Progress::Progress(const py::object& callback) {
  if (callback.is_none()) return;
  // Released with the GIL held, whichever thread drops the last reference.
  state_ = std::shared_ptr<State>(new State{callback, {}, {}}, [](State* s) {
    py::gil_scoped_acquire gil;
    delete s;
  });
}

ProgressFn Progress::function() const {
  if (!state_) return {};
  std::shared_ptr<State> state = state_;
  return [state](std::string_view stage, double fraction) {
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      if (state->error) return;
    }
    py::gil_scoped_acquire gil;
    try {
      state->callback(std::string(stage), fraction);
    } catch (...) {
      std::lock_guard<std::mutex> lock(state->mutex);
      if (!state->error) state->error = std::current_exception();
    }
  };
}

void Progress::rethrow() const {
  if (state_ && state_->error) std::rethrow_exception(state_->error);
}

}  // namespace conform::python
