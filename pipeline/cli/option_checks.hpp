#pragma once
// Checks of option values shared by the subcommands, with short messages
// (CLI11's own range checks print the limits of a double in full).

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace geodual::cli {

/// A finite number >= 0 (no nan, no inf).
CLI::Validator finite_non_negative();
/// A finite number > 0.
CLI::Validator finite_positive();
/// A number in [low, high] (no nan).
CLI::Validator number_between(double low, double high);
/// A finite number > 0, or a percentage: a number in (0, 100] followed by '%'.
CLI::Validator length_or_percentage();
/// An integer in [low, high].
CLI::Validator integer_between(std::int64_t low, std::int64_t high);
/// An unsigned integer given without a sign (CLI11 would wrap "-1" to 2^64 - 1).
CLI::Validator unsigned_integer();

}  // namespace geodual::cli
