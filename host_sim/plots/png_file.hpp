#pragma once
// A cairo picture written as a PNG file by the one temporary-file helper
// (io::replace_file_atomically): never through a link, never half a picture.

#include <cairo.h>

#include <filesystem>

namespace irloc::sim {

// Encodes `surface` as PNG and replaces `png` with it. Throws io::InputError naming the file.
void write_png(const std::filesystem::path& png, cairo_surface_t* surface);

}  // namespace irloc::sim
