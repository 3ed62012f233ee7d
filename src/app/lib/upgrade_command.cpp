// `phos upgrade` (see upgrade_command.h).
#include "app/lib/upgrade_command.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/log.h"
#include "io/image/atomic_write.h"
#include "io/pbrt/upgrade_writer.h"

namespace phos::app {

void run_upgrade(const std::string& input, const std::string& output) {
    std::error_code ec;
    if (std::filesystem::exists(output, ec) && std::filesystem::equivalent(input, output, ec))
        throw InputError("upgrade: the output '" + output +
                         "' is the input; write the pbrt-v4 form elsewhere");
    const std::string text = io::upgrade_pbrt(input, output);  // throws before anything is written
    io::atomic_write(output, [&](const std::string& temp) {
        std::ofstream out(temp, std::ios::binary);
        out << text;
        if (!out.flush()) throw InputError("write failed");
    });
    log::info("phos: wrote " + output);
}

}  // namespace phos::app
