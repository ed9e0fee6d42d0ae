#pragma once
// Which pose source a pose came from: the `source` column of the pose CSV (docs/formats.md).

#include <string_view>

namespace irloc {

enum class SourceKind { dot, square, led, external, fused };

constexpr std::string_view to_string(SourceKind source) {
  switch (source) {
    case SourceKind::dot: return "dot";
    case SourceKind::square: return "square";
    case SourceKind::led: return "led";
    case SourceKind::external: return "external";
    case SourceKind::fused: return "fused";
  }
  return "?";
}

}  // namespace irloc
