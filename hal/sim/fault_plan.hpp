#pragma once
// Faults to inject into a camera stream (irlocd --inject-faults, the reliability tests): what a
// robot's camera and LEDs do wrong, at chosen frames. Written as comma-separated items
// KIND@SEQ+AMOUNT (jump also KIND@SEQ-AMOUNT), each starting at the first frame whose sequence
// number is at least SEQ:
//   lost@SEQ+MS      the camera disconnects; it can be reopened after MS ms; frames exposed
//                    meanwhile are gone
//   late@SEQ+MS      the frame arrives MS ms late (a stalled driver, a starved CPU)
//   drop@SEQ+N       N frames are never delivered (the driver's queue overflowed)
//   dark@SEQ+N       for N frames the LEDs do not light (a dead LED ring or driver)
//   desync@SEQ+N     for N frames the LEDs light out of phase (the strobe lost its sync)
//   jump@SEQ+S       the frame clock jumps by S seconds (signed) from SEQ on

#include <cstdint>
#include <string>
#include <vector>

namespace irloc::hal {

enum class FaultKind { lost, late, drop, dark, desync, jump };

struct Fault {
  FaultKind kind = FaultKind::lost;
  std::uint64_t at_seq = 0;
  std::int64_t amount = 0;  // ms (lost, late), frames (drop, dark, desync), seconds (jump)
};

// Throws io::InputError "--inject-faults ITEM: problem" for an item it cannot read or an amount out
// of range (at most 60 s of delay, 10^6 frames, one year of clock jump, 32 faults).
std::vector<Fault> parse_fault_plan(const std::string& text);

}  // namespace irloc::hal
