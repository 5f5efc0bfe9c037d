#pragma once
// What a Python call hands a job: a path, a numpy array or the object conform.read returns. The pipelines read files
// (the CLI's code path, so the numbers are the CLI's), so geometry in memory is written once to a temporary
// double-precision .ply (exact: the same doubles are read back) that lives as long as the call.

#include <memory>
#include <string>

#include <pybind11/pybind11.h>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/core/progress.h"

namespace conform::python {

namespace py = pybind11;

// What conform.read returns: the mesh (vertices, normals, faces) and what the reader noticed.
struct Geometry {
  Mesh mesh;
  std::vector<std::string> warnings;
  std::string path;
};

class Inputs {
 public:
  Inputs() = default;
  Inputs(const Inputs&) = delete;
  Inputs& operator=(const Inputs&) = delete;
  ~Inputs();

  // A str or os.PathLike as it is; a conform.Geometry, an (N,3) array (points) or a (vertices (V,3), faces (F,3))
  // pair written to a temporary .ply. `what` names the argument in errors. None gives "". Face indices must be
  // integers (integral floats too) in [0, V) and at most 2^31 - 1, or conform.Error names the face and the value.
  std::string geometry(const py::handle& value, const char* what);
  // A path, or a (4,4) array written as a transform file.
  std::string transform(const py::handle& value, const char* what);
  // Whether the named argument was given in memory (its JSON path is then a temporary file, reported as null).
  bool in_memory(const std::string& path) const;

 private:
  std::string temporary(const std::string& name);
  std::string directory_;
  std::vector<std::string> written_;
};

// A str or os.PathLike as a path; None as "".
std::string path_of(const py::handle& value);

// A conform::Error's message as a Python caller reads it: the CLI's flags (--cad-deflection) named as the keyword
// arguments they are (cad_deflection), and a temporary file that holds geometry given in memory named as the argument
// it came from ("the scan argument (given in memory)"), not as a path the caller never saw.
std::string for_python(const std::string& message);

// The CAD keyword arguments of the jobs that read geometry (the CLI's --cad-deflection, --cad-angle-deg,
// --cad-save-mesh): cad_deflection (mm, > 0), cad_angle_deg (in (0, 90]; None: matched to the deflection),
// cad_save_mesh (a path); None leaves the default. Errors name the argument.
void set_cad_options(const py::handle& deflection, const py::handle& angle_deg, const py::handle& save_mesh,
                     CadReadOptions& cad);

// The Python progress callable as a ProgressFn that takes the GIL to call it (from any thread). The first exception
// the callable raises is kept (later calls are skipped) and raised by rethrow() once the job has returned.
class Progress {
 public:
  explicit Progress(const py::object& callback);
  ProgressFn function() const;
  void rethrow() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace conform::python
