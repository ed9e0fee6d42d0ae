#include "hal/sim/fault_plan.hpp"

#include <charconv>
#include <utility>

#include "io/input_error.hpp"

namespace irloc::hal {
namespace {

constexpr std::size_t kMaxFaults = 32;

struct KindInfo {
  const char* name;
  FaultKind kind;
  std::int64_t min_amount;
  std::int64_t max_amount;
  const char* unit;
};

constexpr KindInfo kKinds[] = {
    {"lost", FaultKind::lost, 1, 60'000, "ms"},          {"late", FaultKind::late, 1, 60'000, "ms"},
    {"drop", FaultKind::drop, 1, 1'000'000, "frames"},    {"dark", FaultKind::dark, 1, 1'000'000, "frames"},
    {"desync", FaultKind::desync, 1, 1'000'000, "frames"}, {"jump", FaultKind::jump, -31'536'000, 31'536'000, "s"},
};

bool read_integer(std::string_view digits, std::int64_t& value) {
  if (digits.empty() || digits.size() > 18) return false;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return error == std::errc() && end == digits.data() + digits.size();
}

Fault parse_item(std::string_view item) {
  const auto bad = [&](const std::string& problem) {
    return io::InputError("--inject-faults " + std::string(item) + ": " + problem);
  };
  const std::size_t at = item.find('@');
  if (at == std::string_view::npos) throw bad("expected KIND@SEQ+AMOUNT");
  const std::string_view name = item.substr(0, at);
  const KindInfo* info = nullptr;
  for (const KindInfo& kind : kKinds) {
    if (name == kind.name) info = &kind;
  }
  if (!info) throw bad("unknown fault (expected lost, late, drop, dark, desync or jump)");
  const std::size_t sign = item.find_first_of("+-", at + 1);
  if (sign == std::string_view::npos) throw bad("expected KIND@SEQ+AMOUNT");
  std::int64_t seq = 0;
  std::int64_t amount = 0;
  if (!read_integer(item.substr(at + 1, sign - at - 1), seq) || seq < 0) throw bad("SEQ must be a frame number");
  if (!read_integer(item.substr(sign + 1), amount)) throw bad("AMOUNT must be an integer");
  if (item[sign] == '-') amount = -amount;
  if (amount < info->min_amount || amount > info->max_amount || amount == 0) {
    throw bad("AMOUNT must be " + std::to_string(info->min_amount) + " to " + std::to_string(info->max_amount) + " " +
              info->unit + (info->kind == FaultKind::jump ? ", not 0" : ""));
  }
  return Fault{info->kind, static_cast<std::uint64_t>(seq), amount};
}

}  // namespace

std::vector<Fault> parse_fault_plan(const std::string& text) {
  std::vector<Fault> faults;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    if (faults.size() == kMaxFaults) throw io::InputError("--inject-faults: at most " + std::to_string(kMaxFaults) + " faults");
    faults.push_back(parse_item(std::string_view(text).substr(begin, end - begin)));
    begin = end + 1;
  }
  return faults;
}

}  // namespace irloc::hal
