// The termios serial port on a real pseudo-terminal: raw mode as set, whole messages through,
// and a reader that never reads costs dropped (counted) messages, never a blocked write or a
// torn message.

#include <termios.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "hal/linux/termios_serial.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::hal {
namespace {

// A recognisable 64-byte message: a start byte, its index, then a fill that includes \n and \r.
std::array<std::uint8_t, 64> message(std::uint32_t index) {
  std::array<std::uint8_t, 64> bytes{};
  bytes[0] = 0xFD;
  for (int i = 0; i < 4; ++i) bytes[1 + i] = static_cast<std::uint8_t>(index >> (8 * i));
  for (std::size_t i = 5; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i % 2 == 0 ? '\n' : '\r');
  return bytes;
}

TEST(TermiosSerial, SetsRawModeAndTheBaudRate) {
  test::PseudoTerminal pty;
  TermiosSerial serial(pty.slave_path(), 921600);
  const int fd = ::open(pty.slave_path().c_str(), O_RDONLY | O_NOCTTY);
  ASSERT_GE(fd, 0);
  termios settings{};
  ASSERT_EQ(::tcgetattr(fd, &settings), 0);
  ::close(fd);
  EXPECT_EQ(settings.c_lflag & (ICANON | ECHO | ISIG | IEXTEN), 0u);
  EXPECT_EQ(settings.c_oflag & OPOST, 0u);  // no \n -> \r\n
  EXPECT_EQ(settings.c_iflag & (ICRNL | IXON), 0u);
  EXPECT_EQ(settings.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(settings.c_cflag & (PARENB | CSTOPB | CRTSCTS), 0u);
  EXPECT_EQ(::cfgetospeed(&settings), static_cast<speed_t>(B921600));
}

TEST(TermiosSerial, BytesArriveUnchanged) {
  test::PseudoTerminal pty;
  TermiosSerial serial(pty.slave_path(), 115200);
  std::vector<std::uint8_t> sent;
  for (std::uint32_t i = 0; i < 20; ++i) {
    const auto bytes = message(i);
    ASSERT_TRUE(serial.write_message(bytes));
    sent.insert(sent.end(), bytes.begin(), bytes.end());
  }
  EXPECT_EQ(pty.read_available(), sent);
  EXPECT_EQ(serial.messages_sent(), 20u);
  EXPECT_EQ(serial.messages_dropped(), 0u);
}

TEST(TermiosSerial, AnAbsentReaderCostsWholeMessagesNeverAStall) {
  test::PseudoTerminal pty;  // nobody reads the master until the end
  TermiosSerial serial(pty.slave_path(), 115200, 4096);
  const std::uint32_t count = 20000;  // 1.28 MB: far more than the pty and the queue hold
  test::AllocationCounter counter;
  for (std::uint32_t i = 0; i < count; ++i) serial.write_message(message(i));
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(serial.messages_sent() + serial.messages_dropped(), count);
  EXPECT_GT(serial.messages_dropped(), 0u);
  EXPECT_GT(serial.messages_sent(), 0u);

  // What the reader finally gets is whole messages with increasing indices: the prefix the pty
  // took, then whatever the queue still held.
  std::vector<std::uint8_t> received = pty.read_available();
  serial.flush();
  const std::vector<std::uint8_t> rest = pty.read_available();
  received.insert(received.end(), rest.begin(), rest.end());
  ASSERT_EQ(received.size() % 64, 0u);
  std::int64_t previous = -1;
  for (std::size_t at = 0; at < received.size(); at += 64) {
    const std::uint32_t index = received[at + 1] | received[at + 2] << 8 | received[at + 3] << 16 |
                                static_cast<std::uint32_t>(received[at + 4]) << 24;
    ASSERT_TRUE(std::equal(received.begin() + static_cast<std::ptrdiff_t>(at), received.begin() + static_cast<std::ptrdiff_t>(at + 64),
                           message(index).begin()));
    EXPECT_GT(static_cast<std::int64_t>(index), previous);
    previous = index;
  }
  EXPECT_EQ(received.size() / 64 + serial.queued_bytes() / 64, serial.messages_sent());
}

TEST(TermiosSerial, MissingDeviceIsOneClearError) {
  try {
    TermiosSerial serial("/dev/ttyIRLOC-absent", 115200);
    FAIL() << "opened a missing device";
  } catch (const io::InputError& e) {
    EXPECT_STREQ(e.what(), "serial /dev/ttyIRLOC-absent: cannot open: No such file or directory");
  }
}

// SIGHUP's reopen of a device that is gone (a USB adapter unplugged): the reason is what the
// open said, never errno 0 ("lost (Success)").
TEST(TermiosSerial, AReopenOfAVanishedDeviceKeepsTheReason) {
  test::PseudoTerminal pty;
  const test::TempDir dir;
  std::filesystem::create_symlink(pty.slave_path(), dir / "ttyUSB0");
  TermiosSerial serial((dir / "ttyUSB0").string(), 115200);
  std::filesystem::remove(dir / "ttyUSB0");
  serial.reopen_now();
  EXPECT_FALSE(serial.connected());
  EXPECT_EQ(serial.last_error(), ENOENT);
}

TEST(TermiosSerial, ANonTerminalAndABadBaudAreRefused) {
  EXPECT_THROW(TermiosSerial("/dev/null", 115200), io::InputError);
  test::PseudoTerminal pty;
  EXPECT_THROW(TermiosSerial(pty.slave_path(), 12345), io::InputError);
}

}  // namespace
}  // namespace irloc::hal
