// lumis's command line (app/cli.cpp): subcommands render, compare, diff, warptest and bench.
#pragma once

namespace lumis {

/// Parse the command line, run the chosen command and return the process exit code (0 success, 1 scene or I/O
/// error, 2 usage error; diff: 1 when the images differ).
int run_cli(int argc, char** argv);

}  // namespace lumis
