// tessera._tessera: the extension module of the Python package (python/tessera/__init__.py wraps it).
#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <new>

#include "bindings.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/version.hpp"

namespace py = pybind11;

namespace {

/// The exception classes, made once at import (a translator is a plain function: it cannot capture them).
PyObject* error_class = nullptr;
PyObject* invalid_class = nullptr;
PyObject* io_class = nullptr;
PyObject* topology_class = nullptr;
PyObject* budget_class = nullptr;

/// A new exception class `tessera.<name>` deriving from `bases`; owned by the module (never freed: it lives as long
/// as the interpreter).
PyObject* exception_class(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  PyObject* type = PyErr_NewExceptionWithDoc((std::string("tessera.") + name).c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(type));
  return type;
}

}  // namespace

PYBIND11_MODULE(_tessera, m) {
  m.doc() = "Tessera's C++ core (use the tessera package, which wraps this module)";
  m.attr("__version__") = TESSERA_VERSION_STRING;

  // Tessera's errors as Python exceptions carrying its message (file, line, what was expected); each also derives
  // from the built-in a Python user would catch (ValueError for bad input, OSError for files).
  error_class = exception_class(m, "Error", py::make_tuple(py::handle(PyExc_RuntimeError)),
                                "Base of every error Tessera raises.");
  const auto error_and = [&](PyObject* builtin) {
    return py::make_tuple(py::handle(error_class), py::handle(builtin));
  };
  invalid_class = exception_class(m, "InvalidInput", error_and(PyExc_ValueError),
                                  "Input that breaks a documented precondition: a malformed file, a bad value.");
  io_class = exception_class(m, "IoError", error_and(PyExc_OSError), "A file that cannot be read or written.");
  topology_class = exception_class(m, "TopologyError", error_and(PyExc_ValueError),
                                   "A mesh whose connectivity does not allow the operation.");
  budget_class =
      exception_class(m, "MemoryBudgetError", py::make_tuple(py::handle(invalid_class), py::handle(PyExc_MemoryError)),
                      "A request that would need more memory than the budget allows (refused up front).");
  // NOLINTNEXTLINE(performance-unnecessary-value-param): pybind11's translator type takes the pointer by value
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tessera::MemoryBudgetError& e) {
      PyErr_SetString(budget_class, e.what());
    } catch (const tessera::InvalidInput& e) {
      PyErr_SetString(invalid_class, e.what());
    } catch (const tessera::IoError& e) {
      PyErr_SetString(io_class, e.what());
    } catch (const tessera::TopologyError& e) {
      PyErr_SetString(topology_class, e.what());
    } catch (const tessera::Error& e) {
      PyErr_SetString(error_class, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "tessera: out of memory");
    }
  });

  // A context manager capping the worker threads (tessera.threads(n)): ThreadLimit lives from __enter__ to __exit__.
  struct Threads {
    int count;
    std::unique_ptr<tessera::ThreadLimit> limit;
  };
  py::class_<Threads>(
      m, "threads",
      "with tessera.threads(n): Tessera's parallel loops use at most n threads (0 = all); process-wide, and\n"
      "when caps nest the smallest wins (oneTBB's global_control).")
      .def(py::init([](int n) {
             if (n < 0) throw tessera::InvalidInput(fmt::format("threads: expected a count >= 0, got {}", n));
             return Threads{n, nullptr};
           }),
           py::arg("n"), "A cap of n threads (0: none) for the with-block.")
      .def("__enter__", [](Threads& t) { t.limit = std::make_unique<tessera::ThreadLimit>(t.count); })
      .def("__exit__", [](Threads& t, const py::args&) { t.limit.reset(); });
  m.def("thread_count", &tessera::thread_count, "The number of threads Tessera's parallel loops use now.");
  m.def(
      "set_memory_budget", [](uint64_t bytes) { tessera::MemoryBudget::set_limit(bytes); }, py::arg("bytes"),
      "The most bytes one request may need (the CLI's --max-memory); 0 restores the default, a fraction of the\n"
      "memory this process may use (cgroup limits included). Requests over it raise MemoryBudgetError up front.");
  m.def("memory_budget", &tessera::MemoryBudget::bytes, "The memory budget in bytes (set_memory_budget).");

  tessera::python::bind_images(m);
  tessera::python::bind_meshes(m);
  tessera::python::bind_volumes(m);
  tessera::python::bind_rendering(m);
  tessera::python::bind_sketches(m);
  tessera::python::bind_curves(m);
  tessera::python::bind_fractals(m);
}
