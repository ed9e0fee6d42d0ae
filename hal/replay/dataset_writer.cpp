#include "hal/replay/dataset_writer.hpp"

#include <cstdio>
#include <string>

#include "hal/replay/pgm.hpp"

namespace irloc::hal {
namespace {

constexpr char kIndexHeader[] = "seq,t_ns,led,file\n";

}  // namespace

DatasetWriter::DatasetWriter(const std::filesystem::path& dir, int maxval16)
    : folder_(dir), index_(folder_.create("frames.csv")), index_name_((dir / "frames.csv").string()), maxval16_(maxval16) {
  write_all(index_.get(), kIndexHeader, sizeof kIndexHeader - 1, index_name_);
}

void DatasetWriter::write(const Frame& frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06llu.pgm", static_cast<unsigned long long>(frame.seq));
  const std::string bytes = std::holds_alternative<ImageView8>(frame.image)
                                ? encode_pgm(std::get<ImageView8>(frame.image))
                                : encode_pgm(std::get<ImageView16>(frame.image), maxval16_);
  const UniqueFd file = folder_.create(name);
  write_all(file.get(), bytes.data(), bytes.size(), (dir() / name).string());

  char row[96];
  const int length = std::snprintf(row, sizeof row, "%llu,%lld,%d,%s\n", static_cast<unsigned long long>(frame.seq),
                                   static_cast<long long>(frame.t_ns), frame.led_on ? 1 : 0, name);
  write_all(index_.get(), row, static_cast<std::size_t>(length), index_name_);
}

}  // namespace irloc::hal
