#pragma once
// The foreground's cleaning, the mask the box fit sees: a 3 x 3 opening drops speckle (and rounds
// the silhouette's corners: BoxSilhouette::project allows for it), a 5 x 5 closing fills the
// robot's low-contrast faces. Binary masks (0/255) filtered by SquareMaskFilter: the same result
// as grey Morphology on them, at a cost per pixel independent of the radii.
#include "algo/core/image_view.hpp"
#include "algo/kernels/square_mask_filter.hpp"

namespace irloc::outside_in {

class OpenAndClose {
 public:
  // Scratch for images up to max_width wide, allocated here.
  explicit OpenAndClose(int max_width);

  // Writes mask from foreground (same size, 0/255); scratch is overwritten.
  void apply(ImageView8 foreground, MutableImageView8 scratch, MutableImageView8 mask);

 private:
  SquareMaskFilter open_erode_, open_dilate_, close_dilate_, close_erode_;
};

}  // namespace irloc::outside_in
