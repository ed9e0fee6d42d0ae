#include "firmware/serial_link.hpp"

#include <poll.h>

#include <array>
#include <chrono>

namespace irloc::firmware {
namespace {

constexpr int kPollMs = 50;

}  // namespace

SerialLink::SerialLink(hal::SerialPort& port, PoseStreamEncoder& encoder, std::FILE* log)
    : port_(port), encoder_(encoder), log_(log), thread_([this] { run(); }) {}

SerialLink::~SerialLink() {
  stop_ = true;
  thread_.join();
}

std::int64_t SerialLink::now_ns() {
  // steady_clock is CLOCK_MONOTONIC on Linux: the clock of libcamera's SensorTimestamp.
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::optional<std::int64_t> SerialLink::send_attempt(const PoseEstimate& estimate) {
  const std::lock_guard lock(mutex_);
  const std::span<const std::uint8_t> bytes = encoder_.encode(estimate);
  if (bytes.empty() || !port_.write_message(bytes)) return std::nullopt;
  return now_ns();
}

void SerialLink::warning(std::string_view text) {
  const std::lock_guard lock(mutex_);
  write(encoder_.warning(text));
}

void SerialLink::set_health(LinkHealth health) {
  const std::lock_guard lock(mutex_);
  encoder_.set_health(health);
}

bool SerialLink::connected() {
  const std::lock_guard lock(mutex_);
  return port_.connected();
}

std::uint64_t SerialLink::messages_dropped() {
  const std::lock_guard lock(mutex_);
  return port_.messages_dropped();
}

int SerialLink::last_error() {
  const std::lock_guard lock(mutex_);
  return port_.last_error();
}

void SerialLink::reopen_now() {
  const std::lock_guard lock(mutex_);
  port_.reopen_now();
}

void SerialLink::write(std::span<const std::uint8_t> bytes) {
  if (!bytes.empty()) port_.write_message(bytes);
}

void SerialLink::run() {
  serve(false);  // the first heartbeat as soon as the link is up
  while (!stop_) {
    int fd = -1;
    {
      const std::lock_guard lock(mutex_);
      fd = port_.receive_fd();
    }
    pollfd input{fd, POLLIN, 0};
    const int ready = ::poll(&input, fd >= 0 ? 1 : 0, kPollMs);
    // A hung-up or closed descriptor reports at once: wait as for nothing, the port reopens it.
    const bool input_ready = ready > 0 && (input.revents & POLLIN) != 0;
    if (ready > 0 && !input_ready) std::this_thread::sleep_for(std::chrono::milliseconds(kPollMs));
    serve(input_ready);
  }
}

void SerialLink::serve(bool input_ready) {
  std::array<char, 192> note{};
  std::size_t note_size = 0;
  {
    const std::lock_guard lock(mutex_);
    const std::int64_t now = now_ns();
    if (input_ready) {
      std::array<std::uint8_t, 256> received{};
      const std::size_t size = port_.read_received(received);
      if (size > 0) {
        write(encoder_.receive(std::span(received).first(size), now));
        const std::string_view text = encoder_.receive_note();
        note_size = std::min(text.size(), note.size());
        std::copy_n(text.begin(), note_size, note.begin());
      }
    }
    write(encoder_.tick(now));
  }
  if (note_size > 0) std::fprintf(log_, "irlocd: %.*s\n", static_cast<int>(note_size), note.data());
}

}  // namespace irloc::firmware
