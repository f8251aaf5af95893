#include "text_table.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

namespace geodual::cli {

void KeyValueTable::add(std::string key, std::string value) { rows_.emplace_back(std::move(key), std::move(value)); }

void KeyValueTable::print(std::ostream& out) const {
  std::size_t width = 0;
  for (const auto& [key, value] : rows_) width = std::max(width, key.size());
  for (const auto& [key, value] : rows_) {
    out << key << std::string(width - key.size() + 2, ' ') << value << '\n';
  }
}

ColumnTable::ColumnTable(std::vector<std::string> header) { rows_.push_back(std::move(header)); }

void ColumnTable::add(std::vector<std::string> row) {
  row.resize(rows_.front().size());
  rows_.push_back(std::move(row));
}

void ColumnTable::print(std::ostream& out) const {
  std::vector<std::size_t> widths(rows_.front().size(), 0);
  for (const std::vector<std::string>& row : rows_) {
    for (std::size_t i = 0; i < row.size(); ++i) widths[i] = std::max(widths[i], row[i].size());
  }
  for (const std::vector<std::string>& row : rows_) {
    std::string line;
    for (std::size_t i = 0; i < row.size(); ++i) {
      line += row[i];
      if (i + 1 < row.size()) line += std::string(widths[i] - row[i].size() + 2, ' ');
    }
    out << line << '\n';
  }
}

std::string with_thousands(std::int64_t value) {
  const std::uint64_t magnitude = value < 0 ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
  std::string digits = std::to_string(magnitude);
  for (auto i = static_cast<std::ptrdiff_t>(digits.size()) - 3; i > 0; i -= 3) {
    digits.insert(static_cast<std::size_t>(i), 1, ',');
  }
  return value < 0 ? "-" + digits : digits;
}

std::string significant(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string byte_size(std::uintmax_t bytes) {
  const auto count = with_thousands(static_cast<std::int64_t>(bytes)) + " bytes";
  const double value = static_cast<double>(bytes);
  if (bytes < 1000) return count;
  const char* unit = value < 1e6 ? "kB" : value < 1e9 ? "MB" : "GB";
  const double scaled = value < 1e6 ? value / 1e3 : value < 1e9 ? value / 1e6 : value / 1e9;
  return significant(scaled, 3) + " " + unit + " (" + count + ")";
}

std::string duration(double seconds) {
  if (seconds < 1.0) return significant(seconds * 1e3, 3) + " ms";
  return significant(seconds, 3) + " s";
}

std::string comma_list(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& item : items) list += (list.empty() ? "" : ", ") + item;
  return list;
}

}  // namespace geodual::cli
