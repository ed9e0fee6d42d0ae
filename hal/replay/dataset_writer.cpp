#include "hal/replay/dataset_writer.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "hal/input_error.hpp"
#include "hal/replay/pgm.hpp"

namespace irloc::hal {

DatasetWriter::DatasetWriter(const std::filesystem::path& dir, int maxval16) : dir_(dir), maxval16_(maxval16) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw InputError(dir_.string() + ": cannot create the dataset folder: " + error.message());
  index_.open(dir_ / "frames.csv");
  if (!index_) throw InputError((dir_ / "frames.csv").string() + ": cannot write: " + std::strerror(errno));
  index_ << "seq,t_ns,led,file\n";
}

void DatasetWriter::write(const Frame& frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06llu.pgm", static_cast<unsigned long long>(frame.seq));
  if (const auto* image8 = std::get_if<ImageView8>(&frame.image)) {
    write_pgm(dir_ / name, *image8);
  } else {
    write_pgm(dir_ / name, std::get<ImageView16>(frame.image), maxval16_);
  }
  index_ << frame.seq << ',' << frame.t_ns << ',' << (frame.led_on ? 1 : 0) << ',' << name << '\n';
  index_.flush();
  if (!index_) throw InputError((dir_ / "frames.csv").string() + ": cannot write: " + std::strerror(errno));
}

}  // namespace irloc::hal
