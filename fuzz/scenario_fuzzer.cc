// SPDX-License-Identifier: MIT
// libFuzzer target for the scenario reader: any input must either load or be rejected with
// io::InputError; a crash, a hang, a sanitizer report, an out-of-memory or any other exception
// is a bug. Every loaded variant (a grid gives several) also builds its VA sets, channel
// synthesizer, MPC extractor and its method's estimator, so that the size limits of the
// validation are exercised. Build and run: make fuzz.
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/io/input_error.h"
#include "mirage/io/scenario.h"

namespace {

// A scratch directory per fuzzing process holding the input and a copy of the seminar-room
// example, so that inputs with `extends: seminar_room.yaml` exercise the merge code too.
const std::string& ScratchPath() {
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    const auto dir = std::filesystem::path(tmp != nullptr ? tmp : "/tmp") / ("mirage_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(std::filesystem::path(MIRAGE_SOURCE_DIR) / "examples" / "seminar_room.yaml",
                               dir / "seminar_room.yaml", std::filesystem::copy_options::overwrite_existing);
    return (dir / "input.yaml").string();
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(ScratchPath(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const auto scenario = mirage::io::LoadScenario(ScratchPath());
    for (const auto& variant : scenario.variants) {
      const auto& config = variant.experiment;
      std::vector<mirage::Vec2> anchors_m;
      for (const auto& a : config.anchors) anchors_m.push_back(a.position_m.head<2>());
      (void)mirage::geometry::VirtualAnchorSet::Generate(anchors_m, config.plan, config.channel_max_order);
      const mirage::channel::CirSynthesizer synthesizer(config.channel);
      (void)mirage::dsp::MpcExtractor(config.mpc, synthesizer.pulse(), synthesizer.sample_count(),
                                      config.channel.sample_period_s, config.channel.medium);
      mirage::methods::World world;
      for (const auto& a : config.anchors) world.anchors.push_back({a.id, a.position_m});
      world.floor_plan = config.plan;
      world.channel = config.channel;
      world.mpc = config.mpc;
      world.agents = {"fuzz"};
      (void)config.method.create(world);
    }
  } catch (const mirage::io::InputError&) {
    // Rejected with a message: the expected outcome for bad input.
  }
  return 0;
}
