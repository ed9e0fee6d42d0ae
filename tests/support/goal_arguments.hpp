#pragma once
// The command line of the goal benchmarks (bench_square_goal, bench_led_goal, bench_outside_goal): --scenes=N (N >= 1
// scenes per class) and --seed=S (S >= 0, the scenes' random seed), after Google Benchmark has
// taken its own flags.

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace irloc::test {

// Sets scenes and seed from argv; false (after one line on stderr naming `program` and the
// argument) for anything else.
inline bool read_goal_arguments(const char* program, int argc, char** argv, int& scenes, int& seed) {
  constexpr std::string_view kScenes = "--scenes=", kSeed = "--seed=";
  for (int k = 1; k < argc; ++k) {
    const std::string_view argument(argv[k]);
    const bool is_scenes = argument.starts_with(kScenes), is_seed = argument.starts_with(kSeed);
    const std::size_t prefix = (is_scenes ? kScenes : kSeed).size();
    char* end = nullptr;
    const long value = is_scenes || is_seed ? std::strtol(argv[k] + prefix, &end, 10) : -1;
    if (value < (is_scenes ? 1 : 0) || end == argv[k] + prefix || *end != '\0') {
      std::fprintf(stderr, "%s: unknown argument '%s' (--scenes=N, N >= 1; --seed=S, S >= 0; or a benchmark flag)\n",
                   program, argv[k]);
      return false;
    }
    (is_scenes ? scenes : seed) = static_cast<int>(value);
  }
  return true;
}

}  // namespace irloc::test
