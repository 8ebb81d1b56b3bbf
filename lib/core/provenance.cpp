#include "lib/core/provenance.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <ctime>

#include "wetroad/version.hpp"

namespace wr {

void PhaseTimer::start(const std::string& phase) {
  stop();
  current_ = phase;
  t0_ = std::chrono::steady_clock::now();
}

void PhaseTimer::stop() {
  if (current_.empty()) return;
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  auto it = std::find_if(phases_.begin(), phases_.end(),
                         [&](const auto& p) { return p.first == current_; });
  if (it == phases_.end())
    phases_.emplace_back(current_, dt);
  else
    it->second += dt;
  current_.clear();
}

double PhaseTimer::seconds(const std::string& phase) const {
  for (const auto& [name, t] : phases_)
    if (name == phase) return t;
  return 0.0;
}

double PhaseTimer::total() const {
  double s = 0;
  for (const auto& p : phases_) s += p.second;
  return s;
}

nlohmann::json PhaseTimer::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, t] : phases_) j[name] = t;
  j["total"] = total();
  return j;
}

std::string PhaseTimer::table() const {
  std::size_t w = 5;
  for (const auto& p : phases_) w = std::max(w, p.first.size());
  const double tot = total();
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "  %-*s  %10s  %6s\n", static_cast<int>(w), "phase", "wall [s]", "share");
  out += line;
  for (const auto& [name, t] : phases_) {
    std::snprintf(line, sizeof line, "  %-*s  %10.4f  %5.1f%%\n", static_cast<int>(w), name.c_str(), t,
                  tot > 0 ? 100.0 * t / tot : 0.0);
    out += line;
  }
  std::snprintf(line, sizeof line, "  %-*s  %10.4f\n", static_cast<int>(w), "total", tot);
  out += line;
  return out;
}

std::string utc_now_iso8601() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::size_t peak_rss_bytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<std::size_t>(ru.ru_maxrss) * 1024u;  // Linux reports KiB
}

nlohmann::json Provenance::to_json() const {
  return {{"tool", "wetroad"},      {"version", kVersion},   {"created_utc", utc_now_iso8601()},
          {"command", command},     {"inputs", inputs},      {"parameters", parameters},
          {"model", model},         {"timings", timings}};
}

}  // namespace wr
