// lumis: an offline CPU path tracer. Subcommands: render, compare, diff, warptest, bench (app/cli.cpp).
#include "app/cli.h"

int main(int argc, char** argv) { return lumis::run_cli(argc, argv); }
