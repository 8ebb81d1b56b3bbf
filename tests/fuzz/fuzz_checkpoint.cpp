// libFuzzer: a sweep checkpoint on --resume: the input as sweep.json of one checkpoint (checked
// against a sweep's spec) and as a run record of another, valid one (read back by finished()).
#include <mpi.h>
#include <sanitizer/lsan_interface.h>

#include <filesystem>

#include "lib/sweep/sweep_engine.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

const nlohmann::json& spec() {
  static const nlohmann::json s = {{"coverages", {0, 0.3}}, {"scene", {{"uz", 1e-3}}}, {"surface", {{"synthetic", true}}}};
  return s;
}

// A started checkpoint whose sweep.json is valid: the run records are what is fuzzed.
wr::SweepCheckpoint& started() {
  static wr::SweepCheckpoint* cp = [] {
    const std::string dir = wr::fuzz::scratch_dir() + "/valid.runs";
    std::filesystem::remove_all(dir);
    auto* c = new wr::SweepCheckpoint(dir);
    c->start(spec(), MPI_COMM_SELF);
    return c;
  }();
  return *cp;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  // Open MPI's start-up allocations live until exit by design; at exit LeakSanitizer would
  // report them (through unloaded plug-ins it cannot name). They are not the reader's.
  __lsan_disable();
  MPI_Init(argc, argv);
  __lsan_enable();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // As sweep.json of a checkpoint being resumed.
  const std::string dir = wr::fuzz::scratch_dir() + "/fuzzed.runs";
  std::filesystem::create_directories(dir);
  const std::string sweep_json = wr::fuzz::as_file(data, size, "fuzzed.runs/sweep.json");
  wr::fuzz::expect_clean([&] { wr::SweepCheckpoint(dir).check(spec(), true); });
  // As a finished run's record.
  wr::SweepCheckpoint& cp = started();
  wr::fuzz::as_file(data, size, "valid.runs/run-0000.json");
  wr::fuzz::expect_clean([&] { cp.finished(1); });
  return 0;
}
