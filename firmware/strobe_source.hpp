#pragma once
// The strobe factory: the GPIO line of the board's LED ring, for a camera that needs one.

#include <memory>
#include <optional>
#include <string>

#include "io/config/board_file.hpp"
#include "hal/strobe.hpp"

namespace irloc::firmware {

// The board's GPIO strobe for a live camera that does not drive its own LEDs (see
// open_camera); null for a replayed dataset (frames labelled already) or the simulator (its
// built_in_strobe()). Throws io::InputError when a live camera has no board strobe or the line
// cannot be opened.
std::unique_ptr<hal::Strobe> open_strobe(const std::string& camera_spec, const std::optional<io::BoardStrobe>& board_strobe);

}  // namespace irloc::firmware
