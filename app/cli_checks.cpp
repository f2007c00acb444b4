// Checks of command-line values (app/cli_checks.h), used by app/cli.cpp's CLI11 validators.
#include "app/cli_checks.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

namespace lumis {

std::string empty_problem(const std::string& text, const std::string& expected) {
  return text.empty() ? "expected " + expected + ", found an empty string" : "";
}

bool read_number(const std::string& text, double& value) {
  // As std::stod reads it, except that a number beyond the double range is +-inf (and one below it 0 or subnormal)
  // rather than an exception: CLI11's own conversion turns "1e400" into inf, which the checks must then see.
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

std::string finite_problem(const std::string& text) {
  // CLI11 runs checks before conversion: parse as the option will (a whole string that is a number).
  double v = 0;
  if (read_number(text, v) && !std::isfinite(v)) return "expected a finite number, found " + text;
  return {};  // finite, or not a number: the option's own conversion reports that
}

std::string range_problem(const std::string& text, double lo, double hi, const std::string& expected) {
  double v = 0;
  if (read_number(text, v) && !(v >= lo && v <= hi)) return "expected " + expected + ", found " + text;
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
  const auto is_command = [&](const std::string& word) {
    return std::find(commands.begin(), commands.end(), word) != commands.end();
  };
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word[0] == '-') {
      // lumis's own options take no value; any other option before the command belongs to the command, and
      // CLI11 would call its value ("--spp 2 render": '2') an unknown command.
      if (word == "-h" || word == "--help" || word == "--version") continue;
      for (int j = i + 1; j < argc; ++j)
        if (is_command(argv[j]))
          return "'" + word + "' comes before the command '" + argv[j] + "'; options go after it: lumis " + argv[j] +
                 " " + word + " ...";
      continue;  // no command follows: named below, or CLI11 reports the option
    }
    if (is_command(word)) return {};
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    return "unknown command '" + word + "'; commands: " + list;
  }
  return {};
}

std::string reword_cli11(std::string message) {
  // CLI11 2.1: "--spp: At Most 1 required but received 2" for an option given twice.
  const std::string at_most = ": At Most 1 required but received ";
  const size_t at = message.find(at_most);
  if (at == std::string::npos) return message;
  const size_t digits = at + at_most.size();
  const size_t end = message.find_first_not_of("0123456789", digits);
  const std::string n = message.substr(digits, end - digits);
  return message.substr(0, at) + ": given " + n + " times; give it once" +
         (end == std::string::npos ? "" : message.substr(end));
}

}  // namespace lumis
