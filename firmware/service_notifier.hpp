#pragma once
// systemd's service notification protocol (sd_notify(3)), spoken directly: one datagram per state
// change to the unix socket named by $NOTIFY_SOCKET. irlocd says READY=1 once start-up is done,
// WATCHDOG=1 from its frame loop (so a stalled pipeline misses its pets and systemd restarts it)
// and STOPPING=1 on its way out. Without $NOTIFY_SOCKET (not under systemd) it does nothing.
//
// The protocol is a few lines over a stable, documented socket interface, so irlocd carries it
// itself rather than a runtime dependency on libsystemd. The socket is opened once at start-up
// and every send is non-blocking: the frame loop never waits on the service manager, and a pet
// allocates nothing.

#include <chrono>

namespace irloc::firmware {

class ServiceNotifier {
 public:
  using Clock = std::chrono::steady_clock;

  // Reads $NOTIFY_SOCKET ("/path" or "@abstract") and $WATCHDOG_USEC (with $WATCHDOG_PID, when
  // set, naming this process). Throws io::InputError for a malformed value.
  ServiceNotifier();
  ~ServiceNotifier();
  ServiceNotifier(const ServiceNotifier&) = delete;
  ServiceNotifier& operator=(const ServiceNotifier&) = delete;

  bool active() const { return socket_ >= 0; }
  // The watchdog interval systemd asked for (zero: no watchdog).
  Clock::duration watchdog_interval() const { return watchdog_interval_; }

  void ready() { send("READY=1"); }
  void stopping() { send("STOPPING=1"); }
  // Call once per frame: sends WATCHDOG=1 at most every half watchdog interval.
  void pet(Clock::time_point now);

 private:
  void send(const char* message);

  int socket_ = -1;
  Clock::duration watchdog_interval_{0};
  Clock::time_point last_pet_{};
  bool petted_ = false;
};

}  // namespace irloc::firmware
