#include "option_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace geodual::cli {
namespace {

/// The whole text as a double; false if it is not one.
bool parse_double(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

/// The whole text as an integer; false if it is not one or out of range.
bool parse_integer(const std::string& text, std::int64_t& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

}  // namespace

CLI::Validator finite_non_negative() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (!parse_double(text, value) || !std::isfinite(value) || value < 0) return "must be a finite number >= 0";
        return {};
      },
      "NUMBER >= 0");
}

CLI::Validator number_between(double low, double high) {
  std::ostringstream bounds;
  bounds << '[' << low << ", " << high << ']';
  const std::string range = bounds.str();
  return CLI::Validator(
      [low, high, range](std::string& text) -> std::string {
        double value = 0;
        if (!parse_double(text, value) || !(value >= low && value <= high)) return "must be a number in " + range;
        return {};
      },
      "NUMBER in " + range);
}

CLI::Validator finite_positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (!parse_double(text, value) || !std::isfinite(value) || value <= 0) return "must be a finite number > 0";
        return {};
      },
      "NUMBER > 0");
}

CLI::Validator length_or_percentage() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool percentage = !text.empty() && text.back() == '%';
        double value = 0;
        if (!parse_double(percentage ? text.substr(0, text.size() - 1) : text, value) || !std::isfinite(value) ||
            value <= 0 || (percentage && value > 100)) {
          return "must be a finite number > 0, or a percentage in (0, 100] followed by %";
        }
        return {};
      },
      "LENGTH > 0 or PERCENT%");
}

CLI::Validator integer_between(std::int64_t low, std::int64_t high) {
  const std::string range = std::to_string(low) + " to " + std::to_string(high);
  return CLI::Validator(
      [low, high, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        if (!parse_integer(text, value) || value < low || value > high) return "must be an integer from " + range;
        return {};
      },
      "INTEGER in " + range);
}

CLI::Validator unsigned_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return "must be an integer >= 0";
        }
        char* end = nullptr;
        errno = 0;
        (void)std::strtoull(text.c_str(), &end, 10);
        if (errno == ERANGE) return "must be an integer below 2^64";
        return {};
      },
      "UINT");
}

}  // namespace geodual::cli
