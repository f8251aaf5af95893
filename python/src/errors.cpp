#include "errors.hpp"

#include "geodual/mesh/error.hpp"

namespace geodual::python {
namespace {

// The exception classes, created once at import and alive as long as the module.
PyObject* error_type = nullptr;
PyObject* usage_error_type = nullptr;
PyObject* cancelled_type = nullptr;

PyObject* new_exception(py::module_& module, const char* name, const char* doc, py::tuple bases) {
  const std::string qualified = "geodual." + std::string(name);
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  module.add_object(name, py::reinterpret_borrow<py::object>(type));
  return type;  // the reference PyErr_NewExceptionWithDoc returned stays with us
}

}  // namespace

void add_exceptions(py::module_& module) {
  error_type = new_exception(module, "Error",
                             "Bad input data or an impossible request; the message names the file or argument "
                             "and what is wrong.",
                             py::make_tuple(py::handle(PyExc_RuntimeError)));
  usage_error_type = new_exception(module, "UsageError", "A bad option value (also a ValueError).",
                                   py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError)));
  cancelled_type = new_exception(module, "Cancelled", "The progress callback returned False.",
                                 py::make_tuple(py::handle(error_type)));
  py::register_exception_translator([](std::exception_ptr exception) {
    try {
      if (exception) std::rethrow_exception(exception);
    } catch (const Cancelled& e) {
      PyErr_SetString(cancelled_type, e.what());
    } catch (const UsageError& e) {
      PyErr_SetString(usage_error_type, e.what());
    } catch (const Error& e) {
      PyErr_SetString(error_type, e.what());
    }
  });
}

void throw_cancelled(const std::string& message) {
  PyErr_SetString(cancelled_type, message.c_str());
  throw py::error_already_set();
}

}  // namespace geodual::python
