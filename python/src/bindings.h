#pragma once
// What every job binding shares: result vectors handed to numpy without a copy, the JSON as the CLI prints it, and
// running a job with the GIL released.

#include <algorithm>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "conform/core/output_set.h"
#include "inputs.h"

namespace conform::python {

static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d rows are viewed as (N, 3) doubles");

// A view over `values`, moved to the heap and freed with the array.
template <class T>
inline py::array owned(std::vector<T>&& values) {
  auto* heap = new std::vector<T>(std::move(values));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(heap->size())}, heap->data(), owner);
}

inline py::array owned(std::vector<Eigen::Vector3d>&& rows) {
  auto* heap = new std::vector<Eigen::Vector3d>(std::move(rows));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<Eigen::Vector3d>*>(p); });
  const py::ssize_t n = static_cast<py::ssize_t>(heap->size());
  return py::array_t<double>({n, py::ssize_t{3}}, heap->empty() ? nullptr : heap->front().data(), owner);
}

// The JSON as the CLI prints it (bad UTF-8 replaced), for json.loads on the Python side.
inline std::string text(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// What a job returns to __init__.py: the JSON text, the arrays, and the JSON keys naming inputs given in memory.
inline py::tuple answer(const nlohmann::json& j, const py::dict& arrays,
                        const std::vector<std::string>& in_memory = {}) {
  return py::make_tuple(text(j), arrays, in_memory);
}

// The CLI's file checks for one call (apps/main.cpp, Command::declare_files): every file the call reads and writes
// declared before any work, so an output that is an input (the same path, or the same file through a symbolic or a
// hard link) or that is given twice raises conform.Error then and there; and every file the job writes (the report,
// an export's part files, a generator's companions) staged and renamed together by commit(), all or none. Declare it
// after Inputs has written the in-memory inputs: a file written while it is current waits for its commit().
class CallFiles {
 public:
  CallFiles(std::initializer_list<std::string> inputs, std::initializer_list<std::string> outputs) {
    for (const std::string& path : inputs) files_.add_input(path);
    for (const std::string& path : outputs) files_.add_output(path);
  }
  CallFiles(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs) {
    files_.add_inputs(inputs);
    for (const std::string& path : outputs) files_.add_output(path);
  }
  void commit() { files_.commit(); }

 private:
  OutputSet files_;
};

template <class Run>
auto released(const Progress& progress, Run&& run) {
  auto result = [&] {
    py::gil_scoped_release release;
    return run();
  }();
  progress.rethrow();
  return result;
}

// Keyword arguments the job knows, or TypeError naming the first one it does not (as Python does).
inline void check_keywords(const char* job, const py::kwargs& kw, std::initializer_list<const char*> known) {
  for (const auto& item : kw) {
    const std::string name = py::str(item.first);
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return name == k; })) {
      throw py::type_error(std::string(job) + "() got an unexpected keyword argument '" + name + "'");
    }
  }
}

// The generators of the sicp test data (generator_jobs.cpp): generate_plate, generate_nosecone.
void bind_generator_jobs(py::module_& m);

// conform.inspect (inspect_job.cpp): inspection by the CAD's faces.
void bind_inspect_job(py::module_& m);

// The path-planning jobs (toolpath_jobs.cpp): profile, tube_joint, weld_layers, generate_tube.
void bind_toolpath_jobs(py::module_& m);

}  // namespace conform::python
