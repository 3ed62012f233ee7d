// Interrupts (SIGINT, SIGTERM, the preview window's quit): a process-wide request to stop that
// the render loops poll between units of work (a tile's samples, a photon batch, an iteration).
// The first signal asks the render to stop and write what it has; a second one ends the process
// at once. SIGXFSZ is ignored so that a file-size limit makes a write fail with an error phos
// reports (the previous file intact) instead of killing the process.
#pragma once

namespace phos::interrupt {

// Installs the handlers for SIGINT and SIGTERM (and ignores SIGXFSZ). Idempotent. With `silent`
// the handler says nothing (the MPI ranks other than 0, whose rank 0 says it); `distributed`
// words rank 0's message for an MPI job (whose image needs every rank).
void install_handlers(bool silent = false, bool distributed = false);
// Under MPI, rank 0's processes to look at when a signal arrives: `pids[r]` is rank r's process
// id when it runs on rank 0's machine, else 0 (at most kMaxWatchedRanks are kept). mpirun ends
// the job with SIGTERM when a rank dies; rank 0's handler then names the ranks that are no longer
// running (kill(pid, 0) fails with ESRCH) instead of promising an image it cannot gather.
constexpr int kMaxWatchedRanks = 4096;
void watch_ranks(const int* pids, int count);
// Whether a stop was requested (cheap: one relaxed atomic load; safe from any thread).
bool requested();
// The signal that asked to stop (SIGINT, SIGTERM), or 0 when none did or the request came from
// request() without a signal.
int signal_number();
// Asks the render to stop, as the first signal would (`signo` 0: not a signal, e.g. the preview
// window's quit key).
void request(int signo = 0);
// Forgets a request, so that a process running several renders (the Python module) starts the
// next one afresh. Not for use while a render runs.
void reset();
// The conventional exit status of a process stopped by `signo`: 128 + signo (130 for SIGINT,
// 143 for SIGTERM); 130 when the stop did not come from a signal.
int exit_status(int signo);

}  // namespace phos::interrupt
