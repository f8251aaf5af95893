#pragma once
// A progress callback asked from parallel work. Only the thread that made the
// object asks the callback (so the callback need not be thread-safe); the
// other threads see a refusal through an atomic flag and stop at their next
// check.

#include <atomic>
#include <functional>
#include <thread>

namespace geodual {

class ProgressFromThreads {
 public:
  /// `callback` (may be empty) must outlive this object.
  explicit ProgressFromThreads(const std::function<bool(double)>& callback)
      : callback_(callback), caller_(std::this_thread::get_id()) {}

  /// Whether a call here asks the callback: it is set and this is the thread that made the object.
  bool asks() const { return callback_ && std::this_thread::get_id() == caller_; }

  /// False once refused; where asks(), asks the callback with `fraction` first.
  bool keep_going(double fraction) {
    if (refused()) return false;
    if (!asks() || callback_(fraction)) return true;
    refused_.store(true, std::memory_order_relaxed);
    return false;
  }

  bool refused() const { return refused_.load(std::memory_order_relaxed); }

 private:
  const std::function<bool(double)>& callback_;
  std::thread::id caller_;
  std::atomic<bool> refused_{false};
};

}  // namespace geodual
