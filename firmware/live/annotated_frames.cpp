#include "firmware/live/annotated_frames.hpp"

#include <cstdio>
#include <string>

namespace irloc::firmware {

AnnotatedFrames::AnnotatedFrames(const std::filesystem::path& dir, const Localizer& localizer, int width, int height,
                                 int maxval, LiveImage image)
    : folder_(dir),
      slot_(width, height, maxval),
      publisher_(slot_, localizer, LivePublishing::every_attempt),
      geometry_(live_view_geometry(localizer)),
      image_(image) {}

void AnnotatedFrames::on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                                 const PoseEstimate& estimate) {
  publisher_.on_attempt(pair, verdict, computed, estimate);
  slot_.read(snapshot_);
  draw_live_view(snapshot_, geometry_, image_, snapshot_.width, picture_);
  const std::string jpeg = encoder_.encode(picture_, 90);
  char name[48];
  std::snprintf(name, sizeof name, "attempt_%06llu.jpg", static_cast<unsigned long long>(estimate.seq));
  const io::UniqueFd file = folder_.create(name);
  io::write_all(file.get(), jpeg.data(), jpeg.size(), (folder_.path() / name).string());
  ++written_;
}

}  // namespace irloc::firmware
