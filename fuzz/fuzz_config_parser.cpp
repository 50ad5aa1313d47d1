// Fuzz target: the JSON configuration parser (configs come from players).
// Any input must give a Config or a one-line error, and a parsed config's
// memory estimate must never wrap around.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "sim/memory_estimate.h"
#include "soundpaint/config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const sp::Result<sp::Config> config = sp::parse_config(text, "fuzz.json");
  if (!config.ok()) {
    if (config.error().message.find('\n') != std::string::npos) __builtin_trap();
    return 0;
  }
  const sp::MemoryEstimate estimate = sp::estimate_memory(*config, sp::Backend::Cpu);
  if (estimate.total() < estimate.ring_bytes) __builtin_trap();
  return 0;
}
