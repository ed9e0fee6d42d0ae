// libFuzzer target: the StarGazer host-command parser (firmware/protocol/stargazer_host_commands)
// on arbitrary RX bytes, fed in pieces (each input byte < 32 ends a piece: messages split
// anywhere). Every answer is whole: `~` ... back-quote.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "firmware/protocol/stargazer_host_commands.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  irloc::firmware::StarGazerParameters defaults;
  defaults.version = "irloc";
  defaults.id_count = 3;
  defaults.reference_id = 17;
  defaults.mark_height_mm = 2300;
  irloc::firmware::StarGazerHostCommands commands(defaults);
  std::size_t start = 0;
  for (std::size_t i = 0; i <= size; ++i) {
    if (i < size && data[i] >= 32) continue;
    const std::span<const std::uint8_t> answers = commands.receive(std::span(data + start, i - start));
    if (!answers.empty() && (answers.front() != '~' || answers.back() != '`')) std::abort();
    start = i;
  }
  return 0;
}
