// Command-line options of the progressive integrators (registered on `phos render`).
#include "app/lib/progressive_cli.h"

namespace phos::app {

void add_progressive_options(CLI::App& /*render*/, integrators::ProgressiveOptions& /*options*/) {}

}  // namespace phos::app
