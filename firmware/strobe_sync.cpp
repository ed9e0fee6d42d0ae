#include "firmware/strobe_sync.hpp"
#include "firmware/warning_log.hpp"

#include <cstdio>

namespace irloc::firmware {
namespace {

constexpr unsigned int kSwappedBeforeResync = 2;
constexpr unsigned int kNoContrastWarning = 60;  // about 2 s of pairs at 60 fps

}  // namespace

void StrobeSync::record(const StrobePair& pair, StrobeVerdict verdict) {
  switch (verdict) {
    case StrobeVerdict::verified:
      ++stats_.verified;
      swapped_in_a_row_ = 0;
      no_contrast_in_a_row_ = 0;
      break;
    case StrobeVerdict::swapped:
      ++stats_.swapped;
      no_contrast_in_a_row_ = 0;
      print_warning(stderr, "strobe out of sync: frame %llu (LED off) is brighter than frame %llu (LED on); no pose",
                   static_cast<unsigned long long>(pair.off->seq), static_cast<unsigned long long>(pair.on.seq));
      if (++swapped_in_a_row_ >= kSwappedBeforeResync) {
        schedule_.resync();
        ++stats_.resyncs;
        swapped_in_a_row_ = 0;
        print_warning(stderr, "strobe resynchronised: LED latency now %u frames", schedule_.latency_frames());
      }
      break;
    case StrobeVerdict::no_contrast:
      ++stats_.no_contrast;
      swapped_in_a_row_ = 0;
      if (++no_contrast_in_a_row_ == kNoContrastWarning) {
        print_warning(stderr, "no LED contrast in %u pairs in a row: check the LED ring, its driver and the lens",
                     kNoContrastWarning);
      }
      break;
  }
}

}  // namespace irloc::firmware
