#include "progress_bar.hpp"

#include <unistd.h>
#include <atomic>
#include <csignal>
#include <cstdio>

namespace geodual::cli {
namespace {

volatile std::sig_atomic_t interrupt_flag = 0;

extern "C" void on_interrupt(int) { interrupt_flag = 1; }

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

void catch_interrupts() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
}

bool interrupted() { return interrupt_flag != 0; }

ProgressBar::ProgressBar(bool quiet) : enabled_(!quiet && ::isatty(STDERR_FILENO) == 1) {
  start_ = stage_start_ = last_draw_ = std::chrono::steady_clock::now();
}

ProgressBar::~ProgressBar() { finish(); }

bool ProgressBar::update(std::string_view stage, double fraction) {
  if (interrupted()) return false;
  if (!enabled_) return true;
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    stage_ = std::string(stage);
    stage_start_ = now;
  } else if (seconds_between(last_draw_, now) < 0.1 && fraction < 1.0) {
    return true;
  }
  last_draw_ = now;
  const double elapsed = seconds_between(start_, now), in_stage = seconds_between(stage_start_, now);
  std::string line = "\rgeodual: " + stage_ + " " + std::to_string(static_cast<int>(100 * fraction)) + "%  " +
                     std::to_string(static_cast<int>(elapsed * 10) / 10.0).substr(0, 5) + " s elapsed";
  if (fraction > 0.05 && fraction < 1.0) {
    const double left = in_stage * (1 - fraction) / fraction;
    line += ", about " + std::to_string(static_cast<int>(left * 10) / 10.0).substr(0, 5) + " s left in " + stage_;
  }
  line += "\033[K";
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  return true;
}

void ProgressBar::finish() {
  if (enabled_ && !stage_.empty()) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
    stage_.clear();
  }
}

}  // namespace geodual::cli
