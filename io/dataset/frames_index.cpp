#include "io/dataset/frames_index.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>

#include "io/files/input_file.hpp"
#include "io/input_error.hpp"

namespace irloc::io {
namespace {

// frames.csv of a million frames is about 40 MB.
constexpr std::uint64_t kMaxIndexBytes = 256 << 20;

template <typename Integer>
bool parse_integer(std::string_view text, Integer& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (std::size_t comma; (comma = line.find(',', start)) != std::string_view::npos; start = comma + 1) {
    fields.push_back(line.substr(start, comma - start));
  }
  fields.push_back(line.substr(start));
  return fields;
}

}  // namespace

std::vector<FrameIndexRow> read_frames_index(const std::filesystem::path& dir) {
  const std::filesystem::path index = dir / "frames.csv";
  std::vector<FrameIndexRow> rows;
  const std::string name = index.string();
  const std::string text = read_input_file(index, kMaxIndexBytes);
  std::size_t line_start = 0;
  // The next line of frames.csv without its line end; false at the end of the file.
  const auto next_line = [&](std::string_view& line) {
    if (line_start >= text.size()) return false;
    const std::size_t end = std::min(text.find('\n', line_start), text.size());
    line = std::string_view(text).substr(line_start, end - line_start);
    line_start = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  };

  std::string_view line;
  if (!next_line(line)) throw InputError(name + ":1: empty file, expected the header " + std::string(kFramesCsvHeader));
  if (line != kFramesCsvHeader) {
    throw InputError(name + ":1: expected the header " + std::string(kFramesCsvHeader) + ", got " + std::string(line));
  }

  for (int line_number = 2; next_line(line); ++line_number) {
    if (line.empty()) continue;
    const std::string where = name + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string_view> fields = split_fields(line);
    if (fields.size() != 4) throw InputError(where + "expected 4 fields seq,t_ns,led,file, got " + std::to_string(fields.size()));
    FrameIndexRow row{};
    if (!parse_integer(fields[0], row.seq)) throw InputError(where + "seq: not a non-negative integer: " + std::string(fields[0]));
    if (!parse_integer(fields[1], row.t_ns)) throw InputError(where + "t_ns: not an integer: " + std::string(fields[1]));
    if (fields[2] != "0" && fields[2] != "1") throw InputError(where + "led: expected 0 or 1, got " + std::string(fields[2]));
    row.led_on = fields[2] == "1";
    if (fields[3].empty()) throw InputError(where + "file: empty");
    if (fields[3].find('\0') != std::string_view::npos) throw InputError(where + "file: the name holds a NUL byte");
    row.path = (dir / std::string(fields[3])).string();
    if (!rows.empty()) {
      const FrameIndexRow& previous = rows.back();
      if (row.seq <= previous.seq) {
        throw InputError(where + "seq: " + std::to_string(row.seq) + " does not increase (previous row has " +
                         std::to_string(previous.seq) + ")");
      }
      if (row.t_ns <= previous.t_ns) {
        throw InputError(where + "t_ns: " + std::to_string(row.t_ns) + " does not increase (previous row has " +
                         std::to_string(previous.t_ns) + ")");
      }
    }
    struct stat status {};
    if (::stat(row.path.c_str(), &status) != 0) {
      throw InputError(where + "file: cannot open " + row.path + ": " + std::strerror(errno));
    }
    if (!S_ISREG(status.st_mode)) throw InputError(where + "file: " + row.path + " is not a regular file");
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError(name + ": no frames listed");
  return rows;
}

}  // namespace irloc::io
