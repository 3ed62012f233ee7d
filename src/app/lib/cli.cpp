// Placeholder CLI until the render command lands.
#include "app/lib/cli.h"

namespace phos::app {
int run_cli(int, char**) { return 0; }
}  // namespace phos::app
