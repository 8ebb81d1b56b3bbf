#include "lib/io/staging.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

namespace wr {
namespace fs = std::filesystem;

namespace {

// The one piece of process-wide state in wetroad: signals are delivered to the process, so the
// set of files to remove on one must be reachable from the thread that receives it.
struct StagingSet {
  std::mutex m;
  std::set<std::string> paths;
};

StagingSet& staging_set() {
  static StagingSet s;
  return s;
}

sigset_t cleanup_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "SIGHUP";
  }
}

// Runs in its own thread, outside any signal handler, so removing files (which allocates) is safe.
[[noreturn]] void wait_and_clean(sigset_t set) {
  int sig = 0;
  while (sigwait(&set, &sig) != 0) {
  }
  StagingSet& s = staging_set();
  std::size_t removed = 0;
  {
    std::lock_guard<std::mutex> lock(s.m);
    std::error_code ec;
    for (const std::string& p : s.paths) removed += fs::remove_all(p, ec) > 0;
  }
  std::fprintf(stderr, "wetroad: interrupted (%s); %zu unfinished output%s removed, nothing written\n", signal_name(sig),
               removed, removed == 1 ? "" : "s");
  std::fflush(stderr);
  ::_exit(128 + sig);
}

// "<digits>" at the start of `s`, or 0.
long leading_pid(const std::string& s) {
  long pid = 0;
  std::size_t i = 0;
  for (; i < s.size() && i < 10 && s[i] >= '0' && s[i] <= '9'; ++i) pid = pid * 10 + (s[i] - '0');
  return i > 0 && i < s.size() && s[i] == '-' ? pid : 0;
}

bool process_alive(long pid) { return ::kill(pid_t(pid), 0) == 0 || errno != ESRCH; }

}  // namespace

void track_staging(const std::string& path) {
  StagingSet& s = staging_set();
  std::lock_guard<std::mutex> lock(s.m);
  s.paths.insert(path);
}

void untrack_staging(const std::string& path) {
  StagingSet& s = staging_set();
  std::lock_guard<std::mutex> lock(s.m);
  s.paths.erase(path);
}

void install_interrupt_cleanup() {
  const sigset_t set = cleanup_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread created after this
  std::thread(wait_and_clean, set).detach();
}

namespace {

// Removes the entries of `dir` named "." + something + ".tmp-PID-..." whose PID is dead and whose
// something satisfies `wanted`; returns how many.
template <class Wanted>
std::size_t remove_dead_staging(const fs::path& dir, Wanted wanted) {
  std::error_code ec;
  std::size_t removed = 0;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t tmp = name.rfind(".tmp-");
    if (name.empty() || name[0] != '.' || tmp == std::string::npos || tmp < 1) continue;
    if (!wanted(name.substr(1, tmp - 1))) continue;
    const long pid = leading_pid(name.substr(tmp + 5));
    if (pid <= 0 || pid == long(::getpid()) || process_alive(pid)) continue;
    std::error_code rec;
    removed += fs::remove_all(it->path(), rec) > 0;
  }
  return removed;
}

}  // namespace

std::size_t remove_stale_staging(const std::string& final_path) {
  const fs::path p = fs::path(final_path).lexically_normal();
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string target = p.filename().string();
  return remove_dead_staging(dir, [&](const std::string& of) { return of == target; });
}

std::size_t remove_stale_staging_in(const std::string& dir) {
  return remove_dead_staging(fs::path(dir), [](const std::string&) { return true; });
}

}  // namespace wr
