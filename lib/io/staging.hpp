#pragma once
// Staging files (the `.NAME.tmp-PID-K` siblings that outputs are written to before their rename)
// are removed however a run ends: on an error (the writers and OutputSet), on SIGINT, SIGTERM or
// SIGHUP (a watcher thread below), and, when the process was killed outright (SIGKILL, the OOM
// killer, a power cut), by the next run that writes beside them (remove_stale_staging).
//
// Contract:
//  - track_staging(path) / untrack_staging(path): the set of staging paths this process may
//    leave behind. temporary_sibling() tracks every name it hands out; commit_file() untracks.
//  - install_interrupt_cleanup(): call first thing in main(), before any thread exists (MPI,
//    PETSc, OpenMP, FFTW): blocks SIGINT, SIGTERM and SIGHUP in every thread and starts one
//    thread that waits for them; on one it removes every tracked path (files and staging
//    folders), prints one line on stderr and exits with 128 + the signal (130, 143, 129).
//  - remove_stale_staging(final_path): removes the staging siblings of `final_path` left by
//    processes that no longer exist (the PID in the name is not alive on this host); returns
//    how many it removed. Live processes' staging files are never touched.
#include <cstddef>
#include <string>

namespace wr {

void track_staging(const std::string& path);
void untrack_staging(const std::string& path);
void install_interrupt_cleanup();
std::size_t remove_stale_staging(const std::string& final_path);
// The same for every staging file in `dir` (a sweep's checkpoint folder, whose run records are
// written beside each other).
std::size_t remove_stale_staging_in(const std::string& dir);

}  // namespace wr
