// Checks of command-line values (app/cli_checks.h), used by app/cli.cpp's CLI11 validators.
#include "app/cli_checks.h"

#include <charconv>
#include <cmath>
#include <exception>
#include <system_error>

namespace lumis {

std::string empty_problem(const std::string& text, const std::string& expected) {
  return text.empty() ? "expected " + expected + ", found an empty string" : "";
}

std::string finite_problem(const std::string& text) {
  // CLI11 runs checks before conversion: parse as the option will (a whole string that is a number).
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && !std::isfinite(v)) return "expected a finite number, found " + text;
  } catch (const std::exception&) {  // not a number: the option's own conversion reports it
  }
  return {};
}

std::string range_problem(const std::string& text, double lo, double hi, const std::string& expected) {
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && !(v >= lo && v <= hi)) return "expected " + expected + ", found " + text;
  } catch (const std::exception&) {  // not a number: the option's own conversion reports it
  }
  return {};
}

std::string whole_problem(const std::string& text, long long lo, long long hi) {
  // CLI::Range converts to the option's integer type first and calls "1e3" or "1.5" out of range when that fails.
  long long v = 0;
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || stop != end || v < lo || v > hi)
    return "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], found " + text;
  return {};
}

std::string unknown_command_problem(int argc, const char* const* argv, const std::vector<std::string>& commands) {
  // lumis's own options (--help, --version) take no value: the first other word is the command.
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word[0] == '-') continue;
    std::string list;
    for (const std::string& c : commands) {
      if (c == word) return {};
      list += (list.empty() ? "" : ", ") + c;
    }
    return "unknown command '" + word + "'; commands: " + list;
  }
  return {};
}

}  // namespace lumis
