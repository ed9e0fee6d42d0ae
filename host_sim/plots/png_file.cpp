#include "host_sim/plots/png_file.hpp"

#include <string>

#include "io/files/output_file.hpp"
#include "io/input_error.hpp"

namespace irloc::sim {
namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

void write_png(const std::filesystem::path& png, cairo_surface_t* surface) {
  std::string encoded;
  if (cairo_surface_write_to_png_stream(surface, append, &encoded) != CAIRO_STATUS_SUCCESS) {
    throw io::InputError(png.string() + ": cannot encode the PNG");
  }
  io::replace_file_atomically(png, encoded, 0644, "the PNG");
}

}  // namespace irloc::sim
