#include "firmware/live/jpeg_encoder.hpp"

#include <turbojpeg.h>

#include <stdexcept>

namespace irloc::firmware {

JpegEncoder::JpegEncoder() : handle_(tjInitCompress()) {
  if (handle_ == nullptr) throw std::runtime_error(std::string("TurboJPEG: ") + tjGetErrorStr());
}

JpegEncoder::~JpegEncoder() { tjDestroy(handle_); }

std::string JpegEncoder::encode(const BgrxImage& image, int quality) {
  unsigned char* jpeg = nullptr;
  unsigned long size = 0;
  if (tjCompress2(handle_, image.pixels.data(), image.width, image.stride, image.height, TJPF_BGRX, &jpeg, &size, TJSAMP_420,
                  quality, TJFLAG_FASTDCT) != 0) {
    const std::string message = std::string("TurboJPEG: ") + tjGetErrorStr2(handle_);
    tjFree(jpeg);
    throw std::runtime_error(message);
  }
  std::string bytes(reinterpret_cast<const char*>(jpeg), size);
  tjFree(jpeg);
  return bytes;
}

}  // namespace irloc::firmware
