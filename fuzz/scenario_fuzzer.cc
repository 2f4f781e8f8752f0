// SPDX-License-Identifier: MIT
// libFuzzer target for the scenario readers: any input must either load or be rejected with
// io::InputError; a crash, a hang, a sanitizer report, an out-of-memory or any other exception
// is a bug. A loaded scenario also builds its VA sets, channel synthesizer and MPC extractor,
// so that the size limits of the validation are exercised. Inputs with `method: coop` go to the
// cooperative reader as well, which must then build the channel of its shortest and longest
// variant pulse. Build and run: make fuzz.
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/io/coop_scenario.h"
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
    const auto& config = scenario.mint;
    (void)mirage::geometry::VirtualAnchorSet::Generate(config.anchors_m, config.plan, config.channel_max_order);
    const mirage::channel::CirSynthesizer synthesizer(config.channel);
    (void)mirage::dsp::MpcExtractor(config.mpc, synthesizer.pulse(), synthesizer.sample_count(),
                                    config.channel.sample_period_s);
  } catch (const mirage::io::InputError&) {
    // Rejected with a message: the expected outcome for bad input.
  }
  if (mirage::io::IsCoopScenario(ScratchPath())) {
    try {
      const auto config = mirage::io::LoadCoopScenario(ScratchPath()).config;
      // The channel is checked per pulse duration of the grid; the extremes bound the Nyquist
      // limit and the window's padding.
      const auto [shortest, longest] = std::minmax_element(
          config.variants.begin(), config.variants.end(),
          [](const auto& a, const auto& b) { return a.pulse_duration_s < b.pulse_duration_s; });
      for (const double duration_s : {shortest->pulse_duration_s, longest->pulse_duration_s}) {
        mirage::channel::ChannelOptions channel = config.channel;
        channel.pulse.duration_s = duration_s;
        const mirage::channel::CirSynthesizer synthesizer(channel);
        (void)mirage::dsp::MpcExtractor(config.mpc, synthesizer.pulse(), synthesizer.sample_count(),
                                        channel.sample_period_s);
      }
    } catch (const mirage::io::InputError&) {
      // As above.
    }
  }
  return 0;
}
