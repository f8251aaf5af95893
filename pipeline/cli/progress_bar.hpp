#pragma once
// Progress on a terminal: one line on stderr, rewritten in place
//   geodual: relax  45%  1.2 s elapsed, about 1.5 s left
// and nothing at all when stderr is not a terminal or with --quiet. Ctrl-C
// (SIGINT) asks the running stage to stop: the next progress report cancels.

#include <chrono>
#include <string>
#include <string_view>

namespace geodual::cli {

/// Installs the SIGINT handler (once); interrupted() becomes true on Ctrl-C.
void catch_interrupts();
bool interrupted();
/// A progress callback for work that shows no bar: false once Ctrl-C was pressed.
inline bool still_wanted(double /*fraction*/) { return !interrupted(); }

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Shows `stage` at `fraction`; returns false once Ctrl-C was pressed.
  bool update(std::string_view stage, double fraction);
  /// Clears the line.
  void finish();

 private:
  bool enabled_ = false;
  std::string stage_;
  std::chrono::steady_clock::time_point start_, stage_start_, last_draw_;
};

}  // namespace geodual::cli
