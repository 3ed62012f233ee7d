// TSan builds only (PHOS_SANITIZE=thread): tells ThreadSanitizer where oneTBB synchronises.
//
// Debian's libtbb is not instrumented, so TSan cannot see that a task spawned by one thread and
// run by another was handed over through TBB's queues, nor that a parallel loop's caller waited
// for every task: every parallel loop would be reported as a race. oneTBB reports exactly those
// points to a profiling tool through its ITT hooks; this library is such a tool. TBB loads it
// when INTEL_LIBITTNOTIFY64 names it and INTEL_ITTNOTIFY_GROUPS=sync (scripts/test.sh does so),
// and the phos targets are built with TBB_USE_PROFILING_TOOLS=2 so that the TBB headers they
// inline report spawns and waits too. Each hook becomes a TSan acquire or release:
//  - "releasing" an object (a task being spawned, a finished task's wait counter): release on it;
//  - "acquired" an object (a caller back from waiting on its tasks): acquire on it;
//  - a task starting ("callee enter") or ending ("callee leave"): acquire and release on one
//    shared object, so a stolen task sees what its spawner wrote before spawning it.
// That shared object orders any two tasks that do not overlap in time, so TSan finds races
// between tasks only when they run at the same moment (with two threads, most of a render).
// Nothing here hides a report: scripts/tsan.supp lists the few that remain inside TBB itself.
#include <sanitizer/tsan_interface.h>

namespace {
char g_task_boundary;  // released when a task starts or ends, acquired when one starts
char g_caller;         // the one "stack stitching" handle TBB asks for
}  // namespace

#define PHOS_ITT_EXPORT extern "C" __attribute__((visibility("default")))

// Its presence tells TBB's loader this is a version-1 tool: functions are looked up by name.
PHOS_ITT_EXPORT const int __itt_api_version = 1;

// The "sync" group.
PHOS_ITT_EXPORT void __itt_sync_create(void*, const char*, const char*, int) {}
PHOS_ITT_EXPORT void __itt_sync_rename(void*, const char*) {}
PHOS_ITT_EXPORT void __itt_sync_destroy(void*) {}
PHOS_ITT_EXPORT void __itt_sync_prepare(void*) {}
PHOS_ITT_EXPORT void __itt_sync_cancel(void*) {}
PHOS_ITT_EXPORT void __itt_sync_acquired(void* object) { __tsan_acquire(object); }
PHOS_ITT_EXPORT void __itt_sync_releasing(void* object) {
    __tsan_release(object);
    __tsan_release(&g_task_boundary);
}

// The "stitch" group: TBB calls enter and leave around every task it runs, on every thread.
PHOS_ITT_EXPORT void* __itt_stack_caller_create() { return &g_caller; }
PHOS_ITT_EXPORT void __itt_stack_caller_destroy(void*) {}
PHOS_ITT_EXPORT void __itt_stack_callee_enter(void*) {
    __tsan_acquire(&g_task_boundary);
    __tsan_release(&g_task_boundary);
}
PHOS_ITT_EXPORT void __itt_stack_callee_leave(void*) { __tsan_release(&g_task_boundary); }
