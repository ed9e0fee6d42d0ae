#include "firmware/protocol/stargazer_host_commands.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <optional>

namespace irloc::firmware {
namespace {

constexpr char kStart = '~';
constexpr char kEnd = '`';

std::optional<int> parse_int(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

StarGazerHostCommands::StarGazerHostCommands(const StarGazerParameters& defaults)
    : defaults_(defaults), committed_(defaults), pending_(defaults) {}

std::span<const std::uint8_t> StarGazerHostCommands::receive(std::span<const std::uint8_t> bytes) {
  out_size_ = 0;
  refusal_size_ = 0;
  for (const std::uint8_t byte : bytes) {
    const char c = static_cast<char>(byte);
    if (c == kStart) {  // a new message; an unfinished one before it is dropped
      in_message_ = true;
      message_size_ = 0;
    } else if (!in_message_) {
      continue;
    } else if (c == kEnd) {
      in_message_ = false;
      handle({message_.data(), message_size_});
    } else if (message_size_ < message_.size()) {
      message_[message_size_++] = c;
    } else {
      in_message_ = false;  // longer than any command: noise
    }
  }
  return {out_.data(), out_size_};
}

void StarGazerHostCommands::handle(std::string_view message) {
  if (message.empty()) return;
  const char kind = message.front();
  message.remove_prefix(1);
  const std::size_t bar = message.find('|');
  const std::string_view name = message.substr(0, bar);
  if (kind == '@' && bar == std::string_view::npos) {
    handle_read(name);
  } else if (kind == '#' && bar != std::string_view::npos) {
    handle_write(name, message.substr(bar + 1));
  } else if (kind == '#' && name == "CalcStop") {
    calculating_ = false;
    answer("!", name);
  } else if (kind == '#' && name == "CalcStart") {
    calculating_ = true;
    answer("!", name);
  } else if (kind == '#' && name == "SetEnd") {
    committed_ = pending_;
    answer("!", name);
    answer("!", "ParameterUpdate");
  } else if (kind == '#' && name == "Reset") {
    committed_ = pending_ = defaults_;
    answer("!", name);
    answer("!", "ParameterUpdate");
  } else {
    refuse(name, "not a command irloc knows (CalcStop, CalcStart, SetEnd, Reset)");
  }
}

void StarGazerHostCommands::handle_write(std::string_view name, std::string_view value) {
  const std::optional<int> number = parse_int(value);
  if (name == "MarkHeight") {
    if (!number || *number <= 0 || *number > 20000) return refuse(name, "expects millimetres, 1 to 20000");
    pending_.mark_height_mm = *number;
  } else if (name == "HeightFix") {
    if (value != "Yes" && value != "No") return refuse(name, "expects Yes or No");
    pending_.height_fixed = value == "Yes";
  } else if (name == "MarkMode") {
    if (value != "Map") return refuse(name, "irloc gives map-mode results only (Map)");
  } else if (name == "MarkType") {
    return refuse(name, "irloc's markers are its own (dot, square, LED), set by its map file");
  } else if (name == "BaudRate") {
    if (number != committed_.baud_rate) return refuse(name, "the baud rate is set by the board file or --serial");
  } else if (name == "IDNum") {
    if (number != committed_.id_count) return refuse(name, "the number of markers is set by the map file");
  } else if (name == "RefID") {
    if (number != committed_.reference_id) return refuse(name, "the reference marker is set by the map file");
  } else if (name == "Version") {
    return refuse(name, "read only");
  } else {
    return refuse(name, "not a parameter irloc knows");
  }
  // The sensor acknowledges a write by echoing it.
  std::array<char, 80> echo{};
  const int size = std::snprintf(echo.data(), echo.size(), "%.*s|%.*s", static_cast<int>(name.size()), name.data(),
                                 static_cast<int>(value.size()), value.data());
  answer("!", {echo.data(), static_cast<std::size_t>(std::clamp(size, 0, static_cast<int>(echo.size()) - 1))});
}

void StarGazerHostCommands::handle_read(std::string_view name) {
  std::array<char, 32> value{};
  int size = 0;
  if (name == "Version") size = std::snprintf(value.data(), value.size(), "%.*s", static_cast<int>(committed_.version.size()), committed_.version.data());
  else if (name == "BaudRate") size = std::snprintf(value.data(), value.size(), "%d", committed_.baud_rate);
  else if (name == "IDNum") size = std::snprintf(value.data(), value.size(), "%d", committed_.id_count);
  else if (name == "RefID") size = std::snprintf(value.data(), value.size(), "%d", committed_.reference_id);
  else if (name == "HeightFix") size = std::snprintf(value.data(), value.size(), "%s", committed_.height_fixed ? "Yes" : "No");
  else if (name == "MarkHeight") size = std::snprintf(value.data(), value.size(), "%d", committed_.mark_height_mm);
  else if (name == "MarkType") size = std::snprintf(value.data(), value.size(), "irloc");
  else if (name == "MarkMode") size = std::snprintf(value.data(), value.size(), "Map");
  else return refuse(name, "not a parameter irloc knows");
  answer("!", name);
  answer("$", name, {value.data(), static_cast<std::size_t>(std::clamp(size, 0, static_cast<int>(value.size()) - 1))});
}

// "~" KIND NAME ["|" VALUE] "`", or nothing when the answers of this call fill the buffer (the
// driver asks again).
void StarGazerHostCommands::answer(std::string_view kind, std::string_view name, std::string_view value) {
  const std::size_t size = 2 + kind.size() + name.size() + (value.empty() ? 0 : 1 + value.size());
  if (out_.size() - out_size_ < size) return;
  const auto put = [&](std::string_view text) {
    for (const char c : text) out_[out_size_++] = static_cast<std::uint8_t>(c);
  };
  put("~");
  put(kind);
  put(name);
  if (!value.empty()) {
    put("|");
    put(value);
  }
  put("`");
}

void StarGazerHostCommands::refuse(std::string_view name, std::string_view reason) {
  answer("*", "Refused", name);
  const int size = std::snprintf(refusal_.data(), refusal_.size(), "StarGazer host command %.*s refused: %.*s",
                                 static_cast<int>(name.size()), name.data(), static_cast<int>(reason.size()), reason.data());
  refusal_size_ = static_cast<std::size_t>(std::clamp(size, 0, static_cast<int>(refusal_.size()) - 1));
}

}  // namespace irloc::firmware
