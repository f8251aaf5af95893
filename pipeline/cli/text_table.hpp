#pragma once
// Human-readable output: aligned "key  value" rows, aligned columns and
// number formatting.

#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geodual::cli {

/// Rows of key and value, printed with the values aligned in one column.
class KeyValueTable {
 public:
  void add(std::string key, std::string value);
  void print(std::ostream& out) const;

 private:
  std::vector<std::pair<std::string, std::string>> rows_;
};

/// Rows of cells under a header row, each column as wide as its widest cell.
class ColumnTable {
 public:
  explicit ColumnTable(std::vector<std::string> header);
  /// A row of cells; missing cells are empty, extra ones are not printed.
  void add(std::vector<std::string> row);
  void print(std::ostream& out) const;

 private:
  std::vector<std::vector<std::string>> rows_;  // the header first
};

/// 1234567 -> "1,234,567".
std::string with_thousands(std::int64_t value);

/// A size in bytes for people: "1.33 MB (1,334,607 bytes)".
std::string byte_size(std::uintmax_t bytes);

/// A duration: "12.3 ms", "1.24 s".
std::string duration(double seconds);

/// Seconds elapsed since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The items separated by ", ".
std::string comma_list(const std::vector<std::string>& items);

/// A number with `digits` significant digits, e.g. 0.250246.
std::string significant(double value, int digits = 6);

}  // namespace geodual::cli
