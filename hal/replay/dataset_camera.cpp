#include "hal/replay/dataset_camera.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <span>
#include <cstring>

#include "io/files/input_file.hpp"
#include "io/input_error.hpp"
#include "io/dataset/pgm.hpp"

namespace irloc::hal {
namespace {

// Room for any P5 header in front of the pixels.
constexpr std::size_t kMaxHeaderBytes = 1024;

}  // namespace

DatasetCamera::DatasetCamera(const std::filesystem::path& dir, int width, int height, const std::string& size_source)
    : index_(dir / "frames.csv"), rows_(io::read_frames_index(dir)), width_(width), height_(height), size_source_(size_source) {
  check_first_frame_size();

  const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  for (Slot& slot : slots_) {
    // One byte more than the largest valid file, to notice trailing data.
    slot.file_bytes.resize(kMaxHeaderBytes + 2 * pixels + 1);
    slot.pixels16.resize(pixels);
  }
}

std::vector<std::filesystem::path> DatasetCamera::input_files() const {
  std::vector<std::filesystem::path> files{index_};
  for (const io::FrameIndexRow& row : rows_) files.emplace_back(row.path);
  return files;
}

void DatasetCamera::check_frame_size(const io::PgmHeader& header, const std::string& path) const {
  if (header.width != width_ || header.height != height_) {
    throw io::InputError(path + ": frame is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                     " but the calibration " + size_source_ + " says " + std::to_string(width_) + "x" +
                     std::to_string(height_));
  }
}

// Before the frame buffers and any per-pixel table are sized from the calibration.
void DatasetCamera::check_first_frame_size() {
  const std::string& path = rows_.front().path;
  const io::InputFile file = io::open_input_file(path.c_str(), std::numeric_limits<std::uint64_t>::max());
  std::array<std::byte, kMaxHeaderBytes> header_bytes;
  const std::size_t size = io::read_up_to(file.fd.get(), header_bytes.data(), header_bytes.size(), path.c_str());
  const io::PgmHeader header = io::parse_pgm_header(std::span(header_bytes.data(), size), path);
  check_frame_size(header, path);
  first_depth_bytes_ = header.bytes_per_pixel();
}

void DatasetCamera::read_file(const io::FrameIndexRow& row, Slot& slot, std::size_t& size) const {
  // Opened without blocking (a frame swapped for a FIFO) and refused when it is no regular file
  // or larger than any valid frame plus the one byte that tells trailing data.
  const io::InputFile file = io::open_input_file(row.path.c_str(), slot.file_bytes.size());
  size = io::read_up_to(file.fd.get(), slot.file_bytes.data(), slot.file_bytes.size(), row.path.c_str());
}

bool DatasetCamera::next(Frame& frame) {
  if (next_row_ == rows_.size()) return false;
  const io::FrameIndexRow& row = rows_[next_row_++];
  Slot& slot = slots_[next_slot_];
  next_slot_ = (next_slot_ + 1) % slots_.size();

  std::size_t size = 0;
  read_file(row, slot, size);
  const std::span<const std::byte> bytes(slot.file_bytes.data(), size);
  const io::PgmHeader header = io::parse_pgm_header(bytes, row.path);
  check_frame_size(header, row.path);
  if (header.bytes_per_pixel() != first_depth_bytes_) {
    throw io::InputError(row.path + ": frame is " + std::to_string(8 * header.bytes_per_pixel()) +
                     "-bit but the dataset's first frame is " + std::to_string(8 * first_depth_bytes_) + "-bit");
  }
  const std::size_t available = size - header.pixel_offset;
  if (available < header.pixel_bytes()) {
    throw io::InputError(row.path + ": truncated: " + std::to_string(header.pixel_bytes()) +
                     " bytes of pixels expected, " + std::to_string(available) + " found");
  }
  if (available > header.pixel_bytes()) {
    throw io::InputError(row.path + ": unexpected data after the " + std::to_string(header.pixel_bytes()) + " bytes of pixels");
  }

  frame.seq = row.seq;
  frame.t_ns = row.t_ns;
  frame.led_on = row.led_on;
  const std::byte* pixels = slot.file_bytes.data() + header.pixel_offset;
  unsigned brightest = 0;
  if (header.bytes_per_pixel() == 1) {
    const auto* pixels8 = reinterpret_cast<const std::uint8_t*>(pixels);
    if (header.maxval < 255) brightest = *std::max_element(pixels8, pixels8 + header.pixel_bytes());
    frame.image = ImageView8(pixels8, width_, height_);
  } else {
    std::uint16_t max16 = 0;
    for (std::size_t i = 0; i < slot.pixels16.size(); ++i) {
      slot.pixels16[i] = static_cast<std::uint16_t>((std::to_integer<unsigned>(pixels[2 * i]) << 8) |
                                                     std::to_integer<unsigned>(pixels[2 * i + 1]));
      max16 = std::max(max16, slot.pixels16[i]);
    }
    brightest = max16;
    frame.image = ImageView16(slot.pixels16.data(), width_, height_);
  }
  if (brightest > static_cast<unsigned>(header.maxval)) {
    throw io::InputError(row.path + ": a pixel of " + std::to_string(brightest) + " is above the header's maxval " +
                     std::to_string(header.maxval));
  }
  return true;
}

}  // namespace irloc::hal
