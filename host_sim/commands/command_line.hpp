#pragma once
// irloc-sim's command line: each subcommand is one file in this folder with one function that adds
// it (commands.hpp), its options bound to its own variables and the action that runs it once the
// whole command line has parsed. CLI11 parses (and only command_line.cpp includes it: its
// header-only implementation is most of a source's compile time). Every option's value is checked
// before any work: a text is never empty (an unset shell variable is a mistake, never "the
// default"), a number is finite and within its documented range (docs/simulator.md); a bad option
// exits 2 with CLI11's message naming it. A bad input file throws io::InputError from the action:
// one line, exit 1.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/files/run_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace CLI {
class App;
}

namespace irloc::sim {

enum class Need { optional, required };

class Subcommand {
 public:
  void text(const char* name, std::string& value, const char* description, Need need = Need::optional);
  void integer(const char* name, int& value, const char* description, int low, int high);
  void number(const char* name, double& value, const char* description, double low, double high);
  void integers(const char* name, std::vector<std::uint64_t>& values, const char* description);
  void flag(const char* name, bool& value, const char* description);
  // What the subcommand does; runs only when it was the one chosen and every option parsed.
  void action(std::function<void()> run);

 private:
  friend class CommandLine;
  explicit Subcommand(CLI::App& command) : command_(command) {}
  CLI::App& command_;
};

class CommandLine {
 public:
  explicit CommandLine(const char* description);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  Subcommand add(const char* name, const char* description);
  // Parses and runs the chosen subcommand: 0, 1 (an input error, printed), 2 (a bad command line).
  int run(int argc, char** argv);

 private:
  std::unique_ptr<CLI::App> app_;
};

// The scenario file (the embedded default when `path` is empty; frames > 0 overrides its count),
// with it and every file it names added to `files`' inputs.
Scenario scenario_input(io::RunFiles& files, const std::string& path, int frames);

// A picture tool's scenario (a PNG from a scenario: ledmap, coverage, ledplan), read once the
// picture is known to replace none of its inputs.
Scenario picture_scenario(const std::string& path, const std::string& png);

// A progress bar on stderr when it is a terminal; nothing otherwise (logs stay clean).
Progress progress_bar(const char* what);

}  // namespace irloc::sim
