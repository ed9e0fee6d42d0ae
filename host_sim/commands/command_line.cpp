#include "host_sim/commands/command_line.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "io/input_error.hpp"
#include "host_sim/scenario/default_scenario.hpp"

namespace irloc::sim {
namespace {

const CLI::Validator& non_empty() {
  static const CLI::Validator validator(
      [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "NOT EMPTY");
  return validator;
}

CLI::Validator finite_range(double low, double high) {
  char description[64];
  std::snprintf(description, sizeof description, "FLOAT in [%g, %g]", low, high);
  return CLI::Validator(
      [low, high](const std::string& text) -> std::string {
        double value = 0;
        try {
          std::size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return "not a number: " + text;
        } catch (const std::exception&) {
          return "not a number: " + text;
        }
        if (std::isfinite(value) && value >= low && value <= high) return {};
        char message[120];
        std::snprintf(message, sizeof message, "must be a finite number in [%g, %g], got %s", low, high, text.c_str());
        return message;
      },
      description);
}

}  // namespace

void Subcommand::text(const char* name, std::string& value, const char* description, Need need) {
  CLI::Option* option = command_.add_option(name, value, description)->check(non_empty());
  if (need == Need::required) {
    option->required();
  } else if (!value.empty()) {
    option->capture_default_str();
  }
}

void Subcommand::integer(const char* name, int& value, const char* description, int low, int high) {
  command_.add_option(name, value, description)->check(CLI::Range(low, high));
}

void Subcommand::number(const char* name, double& value, const char* description, double low, double high) {
  command_.add_option(name, value, description)->check(finite_range(low, high));
}

void Subcommand::integers(const char* name, std::vector<std::uint64_t>& values, const char* description) {
  command_.add_option(name, values, description);
}

void Subcommand::flag(const char* name, bool& value, const char* description) { command_.add_flag(name, value, description); }

void Subcommand::action(std::function<void()> run) { command_.callback(std::move(run)); }

CommandLine::CommandLine(const char* description) : app_(std::make_unique<CLI::App>(description)) {
  app_->require_subcommand(1);
}

CommandLine::~CommandLine() = default;

Subcommand CommandLine::add(const char* name, const char* description) {
  return Subcommand(*app_->add_subcommand(name, description));
}

int CommandLine::run(int argc, char** argv) {
  try {
    app_->parse(argc, argv);
    return 0;
  } catch (const CLI::ParseError& e) {
    const int status = app_->exit(e);
    return status == 0 ? 0 : 2;
  } catch (const io::InputError& e) {
    std::fprintf(stderr, "irloc-sim: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "irloc-sim: internal error: %s\n", e.what());
  }
  return 1;
}

Scenario scenario_input(io::RunFiles& files, const std::string& path, int frames) {
  if (!path.empty()) files.input(path);
  Scenario scenario = path.empty() ? parse_scenario(std::string(default_scenario_yaml()), "<default scenario>")
                                   : load_scenario(path);
  if (frames > 0) scenario.frames = frames;
  files.inputs(referenced_files(scenario));
  return scenario;
}

Scenario picture_scenario(const std::string& path, const std::string& png) {
  io::RunFiles files;
  Scenario scenario = scenario_input(files, path, 0);
  files.output_file("--out", png);
  files.check();
  return scenario;
}

Progress progress_bar(const char* what) {
  if (isatty(STDERR_FILENO) == 0) return {};
  return [what](int done, int total) {
    constexpr int kWidth = 40;
    const int filled = done * kWidth / total;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d", what, filled, "########################################",
                 kWidth - filled, "", done, total);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

}  // namespace irloc::sim
