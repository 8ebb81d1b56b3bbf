#pragma once
// Provenance and phase timing: every result records what made it and how long each phase took
// (deal.II-style timing table printed at the end of a run).
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace wr {

// Wall-clock timer over named phases; phases may repeat (their times add up).
class PhaseTimer {
 public:
  // Starts timing `phase`, ending the previous one.
  void start(const std::string& phase);
  void stop();
  double seconds(const std::string& phase) const;
  double total() const;
  const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }
  nlohmann::json to_json() const;  // {"phase": seconds, ..., "total": seconds}
  std::string table() const;       // aligned text table, one phase per line

 private:
  std::vector<std::pair<std::string, double>> phases_;
  std::string current_;
  std::chrono::steady_clock::time_point t0_;
};

// The record stored with every output: tool version, command, inputs, parameters, model,
// timings, time of creation (UTC, ISO 8601).
struct Provenance {
  std::string command;
  nlohmann::json inputs = nlohmann::json::object();
  nlohmann::json parameters = nlohmann::json::object();
  std::string model;
  nlohmann::json timings = nlohmann::json::object();

  nlohmann::json to_json() const;
};

std::string utc_now_iso8601();

// Wall-clock seconds since t0 (steady clock).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Peak resident set size of this process so far, bytes.
std::size_t peak_rss_bytes();

}  // namespace wr
