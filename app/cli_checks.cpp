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
  // An empty value (an unset shell variable) would read as "not given" to CLI11: `diff --threshold "$T"` would pass.
  if (text.empty()) return "expected a finite number, found an empty string";
  double v = 0;
  if (read_number(text, v) && !std::isfinite(v)) return "expected a finite number, found " + text;
  return {};  // finite, or not a number: the option's own conversion reports that
}

std::string range_problem(const std::string& text, double lo, double hi, const std::string& expected) {
  // Each option checked here is checked by finite_problem first, which refuses an empty value. Text that is no
  // number gets the range too (CLI11's conversion would say only "expected a number").
  double v = 0;
  if (!read_number(text, v) || !(v >= lo && v <= hi)) return "expected " + expected + ", found " + text;
  return {};
}

std::string whole_problem(const std::string& text, long long lo, long long hi) {
  // CLI::Range converts to the option's integer type first and calls "1e3" or "1.5" out of range when that fails.
  long long v = 0;
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || stop != end || v < lo || v > hi)
    return "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], found " +
           (text.empty() ? "an empty string" : text);
  return {};
}

namespace {

std::string list_of(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

std::string unknown_command_problem(int argc, const char* const* argv, const std::vector<std::string>& commands) {
  const auto is_command = [&](const std::string& word) {
    return std::find(commands.begin(), commands.end(), word) != commands.end();
  };
  // lumis's own options take no value; any other option before the command belongs to the command.
  const auto is_own = [](const std::string& word) { return word == "-h" || word == "--help" || word == "--version"; };
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word[0] == '-') {
      // CLI11 would call the value of a command's option ("--spp 2 render": '2') an unknown command.
      if (is_own(word)) continue;
      for (int j = i + 1; j < argc; ++j)
        if (is_command(argv[j]))
          return "'" + word + "' comes before the command '" + argv[j] + "'; options go after it: lumis " + argv[j] +
                 " " + word + " ...";
      continue;  // no command follows: named below, or CLI11 reports the option
    }
    if (is_command(word)) return {};
    // "lumis --spp 2": the word is the value of an option that belongs to a command not given.
    if (const std::string option = i > 1 ? argv[i - 1] : ""; !option.empty() && option[0] == '-' && !is_own(option)) {
      std::string message = "'";  // appended, not chained with +: GCC 12 warns of a false overlap (-Wrestrict) there
      message.append(option).append("' is an option of a command; give the command first: lumis COMMAND ");
      return message.append(option).append(" ").append(word).append(" (commands: ").append(list_of(commands)) + ")";
    }
    return "unknown command '" + word + "'; commands: " + list_of(commands);
  }
  return {};
}

std::string reword_cli11(std::string message) {
  // CLI11 2.1: "Could not convert: --time = abc" for a number option given text (whole-number options say so
  // themselves, in whole_problem).
  const std::string convert = "Could not convert: ";
  if (message.rfind(convert, 0) == 0) {
    const size_t eq = message.find(" = ", convert.size());
    const size_t line = message.find('\n');
    if (eq != std::string::npos && eq < line)
      return message.substr(convert.size(), eq - convert.size()) + ": expected a number, found " +
             message.substr(eq + 3, line == std::string::npos ? std::string::npos : line - eq - 3) +
             (line == std::string::npos ? "" : message.substr(line));
  }
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
