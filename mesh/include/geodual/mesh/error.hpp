#pragma once
// Errors a user can cause. Messages name the file (or option), the element or
// line, and what is wrong; the CLI prints them as one line and exits non-zero.

#include <stdexcept>
#include <string>

namespace geodual {

/// Bad input data or an impossible request: the CLI exits with status 1.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad command line or option values: the CLI exits with status 2.
class UsageError : public Error {
 public:
  using Error::Error;
};

/// The computation was cancelled through a progress callback: the CLI exits
/// with status 3 and leaves no partial output.
class Cancelled : public Error {
 public:
  using Error::Error;
};

}  // namespace geodual
