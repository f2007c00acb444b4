// The checks behind lumis's command-line options, apart from app/cli.cpp so that they need no CLI11: each returns
// an empty string for an accepted value, or what is wrong in the option's own terms ("expected ..., found ...").
#pragma once

#include <string>
#include <vector>

namespace lumis {

/// An empty string where a file or camera name is expected (an unset shell variable, `-o ""`): a usage error, not
/// "not given", which would render the default scene or write the default output file.
std::string empty_problem(const std::string& text, const std::string& expected);
/// Reads the whole of `text` as a number (as std::stod, but past the double range as +-inf, not an exception); false
/// when it is not one.
bool read_number(const std::string& text, double& value);
/// A number that is not finite (NaN, inf); other text passes, for the option's own conversion to report.
std::string finite_problem(const std::string& text);
/// Text that is not a number in [lo, hi], described as `expected` ("expected a number of seconds in [0, 1e7], found
/// abc"); an empty value is left to finite_problem, which every option checked here runs first.
std::string range_problem(const std::string& text, double lo, double hi, const std::string& expected);
/// Anything but a whole number in [lo, hi] ("1e3" and "1.5" included): "expected a whole number in [lo, hi], ...".
std::string whole_problem(const std::string& text, long long lo, long long hi);
/// The command line's first word that is not an option, when it names none of `commands`: "unknown command ...";
/// an option other than --help or --version before the command: "'--spp' comes before the command 'render'; ...";
/// an option's value where the command should be ("lumis --spp 2"): "'--spp' is an option of a command; ...".
std::string unknown_command_problem(int argc, const char* const* argv, const std::vector<std::string>& commands);

/// CLI11's message in lumis's words where its own is unclear: an option given twice ("--spp: At Most 1 required but
/// received 2") becomes "--spp: given 2 times; give it once", a number option given text ("Could not convert:
/// --time = abc") "--time: expected a number, found abc". Other messages are returned as they are.
std::string reword_cli11(std::string message);

}  // namespace lumis
