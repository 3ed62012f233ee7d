// The number of threads parallel work runs on from here: the current task arena's concurrency,
// capped by a tbb::global_control (phos render --threads installs one).
#pragma once

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace phos {

inline int worker_threads() {
    return int(std::min(size_t(tbb::this_task_arena::max_concurrency()),
                        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
}

}  // namespace phos
