// SPDX-License-Identifier: MIT
// libFuzzer target for the scenario reader: any input must either load or be rejected with
// io::InputError; a crash, a hang, a sanitizer report or any other exception is a bug.
// Build and run: make fuzz (clang, -fsanitize=fuzzer,address,undefined).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "mirage/io/input_error.h"
#include "mirage/io/scenario.h"

namespace {

// One scratch file per fuzzing process; inputs reach the reader through the file system as in
// `mirage run`.
const std::string& ScratchPath() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr ? dir : "/tmp") + "/mirage_scenario_fuzz_" + std::to_string(getpid()) + ".yaml";
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
    // Small runs keep the parsed experiment cheap; nothing is simulated here.
    (void)mirage::io::LoadScenario(ScratchPath());
  } catch (const mirage::io::InputError&) {
    // Rejected with a message: the expected outcome for bad input.
  }
  return 0;
}
