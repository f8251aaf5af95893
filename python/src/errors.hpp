#pragma once
// The module's exceptions and the translation of geodual's C++ ones:
//   geodual::Error      -> geodual.Error (a RuntimeError), the message as is
//   geodual::UsageError -> geodual.UsageError (a geodual.Error and a ValueError)
//   geodual::Cancelled  -> geodual.Cancelled (a geodual.Error)

#include <pybind11/pybind11.h>

#include <string>

namespace geodual::python {

namespace py = pybind11;

/// Creates geodual.Error, geodual.UsageError and geodual.Cancelled in `module`
/// and registers the translator.
void add_exceptions(py::module_& module);

/// Raises geodual.Cancelled with `message`.
[[noreturn]] void throw_cancelled(const std::string& message);

}  // namespace geodual::python
