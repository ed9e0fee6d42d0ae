#include "hal/replay/dataset_camera.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>

#include "hal/input_error.hpp"
#include "hal/replay/pgm.hpp"

namespace irloc::hal {
namespace {

constexpr std::string_view kHeader = "seq,t_ns,led,file";
// Room for any P5 header in front of the pixels.
constexpr std::size_t kMaxHeaderBytes = 1024;

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

DatasetCamera::DatasetCamera(const std::filesystem::path& dir, int width, int height, const std::string& size_source)
    : width_(width), height_(height), size_source_(size_source) {
  const std::filesystem::path index = dir / "frames.csv";
  const std::string name = index.string();
  std::ifstream in(index);
  if (!in) throw InputError(name + ": cannot open: " + std::strerror(errno));

  std::string line;
  if (!std::getline(in, line)) throw InputError(name + ":1: empty file, expected the header " + std::string(kHeader));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kHeader) throw InputError(name + ":1: expected the header " + std::string(kHeader) + ", got " + line);

  for (int line_number = 2; std::getline(in, line); ++line_number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string where = name + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string_view> fields = split_fields(line);
    if (fields.size() != 4) throw InputError(where + "expected 4 fields seq,t_ns,led,file, got " + std::to_string(fields.size()));
    Row row{};
    if (!parse_integer(fields[0], row.seq)) throw InputError(where + "seq: not a non-negative integer: " + std::string(fields[0]));
    if (!parse_integer(fields[1], row.t_ns)) throw InputError(where + "t_ns: not an integer: " + std::string(fields[1]));
    if (fields[2] != "0" && fields[2] != "1") throw InputError(where + "led: expected 0 or 1, got " + std::string(fields[2]));
    row.led_on = fields[2] == "1";
    if (fields[3].empty()) throw InputError(where + "file: empty");
    row.path = (dir / std::string(fields[3])).string();
    if (!rows_.empty()) {
      const Row& previous = rows_.back();
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
    if (::stat(row.path.c_str(), &status) != 0 || !S_ISREG(status.st_mode)) {
      throw InputError(where + "file: cannot open " + row.path + ": " + std::strerror(errno ? errno : ENOENT));
    }
    rows_.push_back(std::move(row));
  }
  if (rows_.empty()) throw InputError(name + ": no frames listed");

  const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  for (Slot& slot : slots_) {
    // One byte more than the largest valid file, to notice trailing data.
    slot.file_bytes.resize(kMaxHeaderBytes + 2 * pixels + 1);
    slot.pixels16.resize(pixels);
  }
}

void DatasetCamera::read_file(const Row& row, Slot& slot, std::size_t& size) const {
  const int fd = ::open(row.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(row.path + ": cannot open: " + std::strerror(errno));
  size = 0;
  while (size < slot.file_bytes.size()) {
    const ssize_t got = ::read(fd, slot.file_bytes.data() + size, slot.file_bytes.size() - size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      ::close(fd);
      throw InputError(row.path + ": cannot read: " + std::strerror(error));
    }
    if (got == 0) break;
    size += static_cast<std::size_t>(got);
  }
  ::close(fd);
}

bool DatasetCamera::next(Frame& frame) {
  if (next_row_ == rows_.size()) return false;
  const Row& row = rows_[next_row_++];
  Slot& slot = slots_[next_slot_];
  next_slot_ = (next_slot_ + 1) % slots_.size();

  std::size_t size = 0;
  read_file(row, slot, size);
  const std::span<const std::byte> bytes(slot.file_bytes.data(), size);
  const PgmHeader header = parse_pgm_header(bytes, row.path);
  if (header.width != width_ || header.height != height_) {
    throw InputError(row.path + ": frame is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                     " but the calibration " + size_source_ + " says " + std::to_string(width_) + "x" +
                     std::to_string(height_));
  }
  if (first_depth_bytes_ == 0) first_depth_bytes_ = header.bytes_per_pixel();
  if (header.bytes_per_pixel() != first_depth_bytes_) {
    throw InputError(row.path + ": frame is " + std::to_string(8 * header.bytes_per_pixel()) +
                     "-bit but the dataset's first frame is " + std::to_string(8 * first_depth_bytes_) + "-bit");
  }
  const std::size_t available = size - header.pixel_offset;
  if (available < header.pixel_bytes()) {
    throw InputError(row.path + ": truncated: " + std::to_string(header.pixel_bytes()) +
                     " bytes of pixels expected, " + std::to_string(available) + " found");
  }
  if (available > header.pixel_bytes()) {
    throw InputError(row.path + ": unexpected data after the " + std::to_string(header.pixel_bytes()) + " bytes of pixels");
  }

  frame.seq = row.seq;
  frame.t_ns = row.t_ns;
  frame.led_on = row.led_on;
  const std::byte* pixels = slot.file_bytes.data() + header.pixel_offset;
  if (header.bytes_per_pixel() == 1) {
    frame.image = ImageView8(reinterpret_cast<const std::uint8_t*>(pixels), width_, height_);
  } else {
    for (std::size_t i = 0; i < slot.pixels16.size(); ++i) {
      slot.pixels16[i] = static_cast<std::uint16_t>((std::to_integer<unsigned>(pixels[2 * i]) << 8) |
                                                     std::to_integer<unsigned>(pixels[2 * i + 1]));
    }
    frame.image = ImageView16(slot.pixels16.data(), width_, height_);
  }
  return true;
}

}  // namespace irloc::hal
