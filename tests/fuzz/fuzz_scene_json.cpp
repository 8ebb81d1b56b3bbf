// libFuzzer: a scene JSON (--scene): its "surface" block resolved and validated as `synth` and
// the sweeps do before synthesizing.
#include "app/synth_options.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = wr::fuzz::as_file(data, size, "scene.json");
  // The options as `synth --scene FILE` leaves them (built once: the scene file is what varies).
  static CLI::App app;
  static wr::app::SynthOptions opt;
  static const bool parsed = [&] {
    wr::app::add_synth_options(app, opt);
    std::vector<std::string> args = {path, "--scene"};  // CLI11 parses a reversed vector
    app.parse(args);
    return true;
  }();
  (void)parsed;
  wr::fuzz::expect_clean([&] { wr::validate(wr::app::resolve_synth_options(opt)); });
  return 0;
}
