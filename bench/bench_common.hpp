#pragma once
// What the benchmarks share: a wall clock, a synthesized surface as if loaded from a file, and
// running a measurement in a forked child so that the peak memory it reports is its own.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "roads/surface_import.hpp"
#include "roads/synthesize.hpp"

namespace wr::bench {

inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

inline LoadedSurface as_loaded(SynthResult&& r) {
  LoadedSurface s;
  s.source = "(in memory)";
  s.format = "memory";
  s.dropout.assign(r.map.h.size(), 0);
  s.synthesis = SynthesisRecord{r.psd, r.k_eq44, r.h0_eq44_on_lattice, 1, 1};
  s.map = std::move(r.map);
  return s;
}

// Runs f() in a forked child and returns its JSON, so that the peak memory it reports is its own.
template <class F>
nlohmann::json in_child(F f) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::string s;
    try {
      s = f().dump();
    } catch (const std::exception& e) {
      s = nlohmann::json{{"error", e.what()}}.dump();
    }
    const char* p = s.data();
    std::size_t left = s.size();
    while (left > 0) {
      const ssize_t w = write(fd[1], p, left);
      if (w <= 0) break;
      p += w;
      left -= static_cast<std::size_t>(w);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string buf;
  char chunk[4096];
  ssize_t got;
  while ((got = read(fd[0], chunk, sizeof chunk)) > 0) buf.append(chunk, static_cast<std::size_t>(got));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return buf.empty() ? nlohmann::json{{"error", "child failed"}} : nlohmann::json::parse(buf);
}

}  // namespace wr::bench
