#pragma once
// Internal: walking a text buffer line by line and a line word by word, for
// the text formats (OBJ, OFF, ASCII PLY and STL, PLY headers). No copies, no
// locale: every piece is a std::string_view into the file's bytes.

#include <cstddef>
#include <cstring>
#include <string_view>

namespace geodual::io::detail {

/// Space, tab and the other ASCII blanks that may separate words ('\n' ends lines).
constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Lines of a text ended by "\n" or "\r\n"; the last line may lack its end.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text, std::size_t first_line_number = 1)
      : text_(text), line_number_(first_line_number - 1) {}

  /// The next line without its terminator; false when the text is exhausted.
  bool next(std::string_view& line) {
    if (offset_ >= text_.size()) {
      return false;
    }
    const char* begin = text_.data() + offset_;
    const std::size_t left = text_.size() - offset_;
    const void* newline = std::memchr(begin, '\n', left);
    std::size_t length = newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - begin) : left;
    offset_ += newline ? length + 1 : length;
    if (length > 0 && begin[length - 1] == '\r') {
      --length;
    }
    line = std::string_view(begin, length);
    ++line_number_;
    return true;
  }

  /// 1-based number of the line `next` returned last.
  std::size_t line_number() const { return line_number_; }
  /// Bytes consumed so far, terminators included.
  std::size_t offset() const { return offset_; }

 private:
  std::string_view text_;
  std::size_t offset_ = 0;
  std::size_t line_number_;
};

/// The blank-separated words of one line.
class WordCursor {
 public:
  explicit WordCursor(std::string_view line) : rest_(line) {}

  /// The next word; false when only blanks are left.
  bool next(std::string_view& word) {
    skip_blanks();
    if (rest_.empty()) {
      return false;
    }
    std::size_t length = 1;
    while (length < rest_.size() && !is_blank(rest_[length])) {
      ++length;
    }
    word = rest_.substr(0, length);
    rest_.remove_prefix(length);
    return true;
  }

  /// True when only blanks are left.
  bool at_end() {
    skip_blanks();
    return rest_.empty();
  }

  /// What is left of the line, leading blanks removed.
  std::string_view rest() {
    skip_blanks();
    return rest_;
  }

 private:
  void skip_blanks() {
    while (!rest_.empty() && is_blank(rest_.front())) {
      rest_.remove_prefix(1);
    }
  }

  std::string_view rest_;
};

/// The line up to its first `marker` (comments in OBJ and OFF start with '#').
constexpr std::string_view strip_comment(std::string_view line, char marker = '#') {
  const std::size_t at = line.find(marker);
  return at == std::string_view::npos ? line : line.substr(0, at);
}

/// True when the line holds nothing but blanks.
constexpr bool is_blank_line(std::string_view line) {
  for (const char c : line) {
    if (!is_blank(c)) {
      return false;
    }
  }
  return true;
}

}  // namespace geodual::io::detail
