#include "cancellation.hpp"

#include "errors.hpp"

#include <utility>

namespace geodual::python {

ProgressBridge::ProgressBridge(py::object callable) : callable_(std::move(callable)) {
  if (!callable_.is_none() && !PyCallable_Check(callable_.ptr())) {
    throw py::type_error("progress must be a callable progress(stage, fraction) or None");
  }
}

bool ProgressBridge::operator()(std::string_view stage, double fraction) {
  py::gil_scoped_acquire acquire;
  if (error_ || refused_) return false;
  try {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C: KeyboardInterrupt
    // The callable hears of each stage, of each percent done and of the end,
    // not of each of geodual's (frequent) checks.
    const bool news =
        stage != last_stage_ || fraction >= last_fraction_ + 0.01 || (fraction >= 1 && last_fraction_ < 1);
    if (callable_.is_none() || !news) return true;
    last_stage_ = stage;
    last_fraction_ = fraction;
    const py::object answer = callable_(py::str(stage.data(), stage.size()), fraction);
    if (!answer.is_none() && !answer.cast<bool>()) refused_ = true;
  } catch (py::error_already_set& error) {
    error_.emplace(std::move(error));
  } catch (const py::cast_error&) {
    refused_ = true;  // an answer that is not a truth value: stop rather than guess
  }
  return !error_ && !refused_;
}

void ProgressBridge::raise_stop(const char* message) {
  if (error_) {
    py::error_already_set error = std::move(*error_);
    error_.reset();
    throw error;
  }
  if (refused_) throw_cancelled(std::string(message) + " (the progress callback returned False)");
}

}  // namespace geodual::python
