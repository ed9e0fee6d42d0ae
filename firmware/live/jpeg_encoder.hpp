#pragma once
// JPEG encoding of the live view's pictures with libjpeg-turbo's TurboJPEG API.

#include <cstdint>
#include <string>

#include "firmware/live/live_drawing.hpp"

namespace irloc::firmware {

class JpegEncoder {
 public:
  JpegEncoder();  // throws std::runtime_error when TurboJPEG cannot start
  ~JpegEncoder();
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;

  // `quality` 1..100; 4:2:0 chroma. Throws std::runtime_error with TurboJPEG's message.
  std::string encode(const BgrxImage& image, int quality);

 private:
  void* handle_;
};

}  // namespace irloc::firmware
