#pragma once
// Long computations run without the GIL; geodual's progress callbacks (asked
// on the calling thread) take it back to check for Ctrl-C and to call the
// caller's Python progress callable. What stops the computation is raised in
// Python once it has unwound: KeyboardInterrupt (or whatever the callable
// raised) as itself, a False from the callable as geodual.Cancelled.

#include "geodual/mesh/error.hpp"

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <string_view>

namespace geodual::python {

namespace py = pybind11;

class ProgressBridge {
 public:
  /// `callable`: None, or progress(stage: str, fraction: float) returning
  /// None/True to go on and False to cancel.
  explicit ProgressBridge(py::object callable);

  /// For geodual's callbacks; called without the GIL. Returns false to cancel.
  bool operator()(std::string_view stage, double fraction);

  /// Runs `compute()` without the GIL and returns its result. A stop this
  /// bridge caused is raised as the Python exception behind it, whatever
  /// geodual error the computation unwound with.
  template <class Compute>
  auto run(Compute&& compute) -> decltype(compute());

 private:
  /// With the GIL: raises what stopped the computation (`message`: geodual's
  /// error), if this bridge did; returns otherwise.
  void raise_stop(const char* message);

  py::object callable_;
  std::optional<py::error_already_set> error_;  ///< what the callable or Ctrl-C raised
  bool refused_ = false;                        ///< the callable returned False
  std::string last_stage_;
  double last_fraction_ = -1;
};

}  // namespace geodual::python

template <class Compute>
auto geodual::python::ProgressBridge::run(Compute&& compute) -> decltype(compute()) {
  try {
    py::gil_scoped_release release;
    return compute();
  } catch (const Error& error) {
    raise_stop(error.what());  // the GIL is held again here
    throw;
  }
}
