// The `phos` command line: sub-commands, option parsing (CLI11), error reporting and exit codes.
#pragma once

namespace phos::app {

// Runs the command line; returns the process exit code (0 ok, 2 bad input, 1 internal failure).
int run_cli(int argc, char** argv);

}  // namespace phos::app
