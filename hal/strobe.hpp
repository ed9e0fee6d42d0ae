#pragma once
// The IR LED ring's switch. The firmware decides which frames are lit (firmware/strobe_schedule);
// a backend only drives the line.

namespace irloc::hal {

class Strobe {
 public:
  virtual ~Strobe() = default;

  // Switches the LEDs on or off now. Must not block for longer than a GPIO write (microseconds);
  // allocates nothing. A device failure throws io::InputError naming the device.
  virtual void set_led(bool on) = 0;
};

}  // namespace irloc::hal
