// lumis: an offline CPU path tracer. Subcommands: render, compare, diff, warptest, bench.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <system_error>

#include "app/cli.h"


int main(int argc, char** argv) {
  CLI::App app{"lumis: an offline path tracer built on the importance-sampling lecture's estimators"};
  app.set_version_flag("--version", std::string("lumis ") + LUMIS_VERSION);
  app.require_subcommand(1);
  // Usage errors start with "lumis: ", as every other message does.
  app.failure_message(
      [](const CLI::App* a, const CLI::Error& e) { return "lumis: " + CLI::FailureMessage::simple(a, e); });
  // Past a file-size limit (ulimit -f), a write fails with EFBIG and lumis names the file; the default action of
  // SIGXFSZ would instead kill it with a core dump and leave its temporary file behind.
  std::signal(SIGXFSZ, SIG_IGN);
  int exit_code = 0;
  lumis::register_render_command(app, exit_code);
  lumis::register_warptest_command(app, exit_code);
  lumis::register_diff_command(app, exit_code);
  lumis::register_compare_command(app, exit_code);
  lumis::register_bench_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  // Output lost to a full disk (`lumis diff --json > metrics.json`) must not pass for success, as in coreutils.
  // diff's errors exit 2, since its 1 means "the images differ"; every other command's I/O errors exit 1.
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    const std::string why = errno ? ": " + std::generic_category().message(errno) : "";
    std::cerr << "lumis: cannot write the standard output" << why << "\n";
    return app.got_subcommand("diff") ? 2 : 1;
  }
  return exit_code;
}
