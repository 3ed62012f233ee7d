// Entry point of the `phos` command: hands over to the CLI in app/lib.
#include "app/lib/cli.h"

int main(int argc, char** argv) { return phos::app::run_cli(argc, argv); }
