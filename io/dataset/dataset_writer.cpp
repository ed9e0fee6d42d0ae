#include "io/dataset/dataset_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "io/dataset/frames_index.hpp"
#include "io/input_error.hpp"
#include "io/dataset/pgm.hpp"

namespace irloc::io {
namespace {


}  // namespace

DatasetWriter::DatasetWriter(const std::filesystem::path& dir, int maxval16)
    : folder_(dir), index_(folder_.create("frames.csv")), index_name_((dir / "frames.csv").string()), maxval16_(maxval16) {
  const std::string header = std::string(kFramesCsvHeader) + "\n";
  write_all(index_.get(), header.data(), header.size(), index_name_);
  index_end_ = header.size();
}

void DatasetWriter::write(const Frame& frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06llu.pgm", static_cast<unsigned long long>(frame.seq));
  const std::string bytes = std::holds_alternative<ImageView8>(frame.image)
                                ? encode_pgm(std::get<ImageView8>(frame.image))
                                : encode_pgm(std::get<ImageView16>(frame.image), maxval16_);
  const std::filesystem::path file_path = dir() / name;
  try {
    const UniqueFd file = folder_.create(name);
    write_all(file.get(), bytes.data(), bytes.size(), file_path.string());
  } catch (const InputError&) {
    std::error_code ignored;  // the write's error is the one to report
    std::filesystem::remove(file_path, ignored);  // a partial frame is no frame of the dataset
    throw;
  }

  char row[96];
  const int length = std::snprintf(row, sizeof row, "%llu,%lld,%d,%s\n", static_cast<unsigned long long>(frame.seq),
                                   static_cast<long long>(frame.t_ns), frame.led_on ? 1 : 0, name);
  try {
    write_all(index_.get(), row, static_cast<std::size_t>(length), index_name_);
  } catch (const InputError&) {
    // frames.csv ends with its last whole row, and lists only frames whose PGM is on disk.
    if (::ftruncate(index_.get(), static_cast<off_t>(index_end_)) == 0) {
      ::lseek(index_.get(), static_cast<off_t>(index_end_), SEEK_SET);
    }
    std::error_code ignored;
    std::filesystem::remove(file_path, ignored);
    throw;
  }
  index_end_ += static_cast<std::size_t>(length);
  ++frames_written_;
}

}  // namespace irloc::io
