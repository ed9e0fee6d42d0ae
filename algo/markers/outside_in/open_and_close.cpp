#include "algo/markers/outside_in/open_and_close.hpp"

namespace irloc::outside_in {

OpenAndClose::OpenAndClose(int max_width)
    : open_erode_(max_width, 1, SquareMaskFilter::Operation::erode),
      open_dilate_(max_width, 1, SquareMaskFilter::Operation::dilate),
      close_dilate_(max_width, 2, SquareMaskFilter::Operation::dilate),
      close_erode_(max_width, 2, SquareMaskFilter::Operation::erode) {}

void OpenAndClose::apply(ImageView8 foreground, MutableImageView8 scratch, MutableImageView8 mask) {
  open_erode_.apply(foreground, scratch);
  open_dilate_.apply(scratch, mask);
  close_dilate_.apply(mask, scratch);
  close_erode_.apply(scratch, mask);
}

}  // namespace irloc::outside_in
