#pragma once
// A horizontal run of foreground pixels: [x_begin, x_end) of row y. The run extractors
// (FusedFrontEnd, BlobLabeller) emit them in raster order; the square path's tape mask reads the
// shared pass's runs instead of thresholding the pair a second time.

namespace irloc {

struct PixelRun {
  int y;
  int x_begin;
  int x_end;  // exclusive
};

}  // namespace irloc
