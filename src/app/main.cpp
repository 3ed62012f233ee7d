// Entry point of the `phos` command: hands over to the CLI in app/lib (under an MPI launcher, once
// MPI is started: docs/distributed.md).
#include "app/lib/cli.h"
#include "dist/ranks.h"

int main(int argc, char** argv) {
    phos::dist::init(&argc, &argv);
    const int code = phos::app::run_cli(argc, argv);
    phos::dist::finalize();
    return code;
}
