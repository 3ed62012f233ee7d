#!/usr/bin/env bash
# Installs what is missing, builds phos and runs the whole test suite.
#
# scripts/test.sh --sanitize runs the sanitizers instead (docs/testing.md, "Sanitizers"); only the
# first step with --sanitize=address, only the second with --sanitize=thread:
#  1. the whole suite built with ASan + UBSan in build-asan (its tests run its own sanitized phos);
#  2. the threaded tests built with TSan in build-tsan. Every render uses all cores, but the whole
#     suite under TSan takes far longer, so "threaded tests" are those that exist to exercise
#     threads (the ctest -R pattern below): names with "Thread" (the 1-versus-2-thread
#     determinism tests of the pixel loop, photon tracing, k-d tree and beam BVH builds, volume
#     cache, SPPM, media integrators and command line; the progress bar and Embree queries from
#     several std::threads), the preview window and tev streaming (a thread each beside the
#     render) and the interrupt tests (signal handlers during a threaded render).
# Any sanitizer report fails the test that produced it. Suppressions, for the uninstrumented
# third-party libraries only: scripts/lsan.supp and scripts/tsan.supp.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

case "${1:-}" in
  --sanitize) asan=1 tsan=1 ;;
  --sanitize=address) asan=1 tsan=0 ;;
  --sanitize=thread) asan=0 tsan=1 ;;
  *) asan=0 tsan=0 ;;
esac
if [ $asan = 1 ]; then
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1"
  export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  PHOS_CMAKE_ARGS="-DPHOS_SANITIZE=address,undefined -DPHOS_BUILD_BENCH=OFF" \
    "$here/scripts/setup.sh" "$here/build-asan"
  # Memory.* compares peak RSS with phos's own estimate, which ASan's shadow memory makes
  # meaningless. Preview.* and PhotonViewer.* open a window under Xvfb: Mesa's GL driver leaks a
  # little and is unloaded before exit; Mpi.* run phos under mpirun: OpenMPI's plugins leak their
  # start-up strings and are unloaded before exit too. LSan cannot name an unloaded library in a
  # suppression, so these run with leak detection off (and every other check on).
  unloaded='^(Preview|PhotonViewer|Mpi)\.'
  (cd "$here/build-asan" && ctest --output-on-failure -j"$(nproc)" -E "^Memory\.|$unloaded")
  (cd "$here/build-asan" && ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" ctest --output-on-failure -R "$unloaded")
fi
if [ $tsan = 1 ]; then
  # ignore_noninstrumented_modules: no memory accesses are recorded for malloc, free, memcpy...
  # called from the uninstrumented libraries (Embree's own allocations otherwise look racy).
  export TSAN_OPTIONS="suppressions=$here/scripts/tsan.supp:print_suppressions=0:second_deadlock_stack=1:ignore_noninstrumented_modules=1"
  PHOS_CMAKE_ARGS="-DPHOS_SANITIZE=thread -DPHOS_BUILD_BENCH=OFF" "$here/scripts/setup.sh" "$here/build-tsan"
  # oneTBB loads this bridge, which shows TSan where TBB synchronises (cmake/tsan_tbb_bridge.cpp).
  export INTEL_LIBITTNOTIFY64="$here/build-tsan/libphos_tsan_tbb_bridge.so" INTEL_ITTNOTIFY_GROUPS=sync
  # Interrupt.SecondSignalExitsAtOnce is left out: it runs no threads (it raises SIGINT twice in a
  # child forked from the test process), and under TSan that child exits 0 instead of 130.
  (cd "$here/build-tsan" && ctest --output-on-failure -j"$(nproc)" -R 'Thread|^Preview\.|^TevRender\.|^Interrupt\.' \
    -E '^Interrupt\.SecondSignalExitsAtOnce$')
fi
if [ $asan = 1 ] || [ $tsan = 1 ]; then exit 0; fi

"$here/scripts/setup.sh" "$here/build"
cd "$here/build"
ctest --output-on-failure -j"$(nproc)"
