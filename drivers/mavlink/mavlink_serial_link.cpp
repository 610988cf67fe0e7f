// Serial port handling for the MAVLink link: raw termios, O_NONBLOCK reads and whole-frame writes,
// so the caller's loop never waits on the port.
#include "drivers/mavlink/mavlink_serial_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace rovctl::drivers::mavlink {

namespace {

speed_t to_speed(std::uint32_t baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1500000:
      return B1500000;
    default:
      return B0;
  }
}

}  // namespace

bool parse_serial_endpoint(std::string_view text, std::string_view config_key, SerialEndpoint& out,
                           std::string& error) {
  const auto fail = [&](const std::string& why) {
    error = std::string(config_key) + ": '" + std::string(text) + "' " + why +
            " (expected serial:DEVICE:BAUD, e.g. serial:/dev/ttyACM0:115200)";
    return false;
  };
  constexpr std::string_view kPrefix = "serial:";
  if (text.substr(0, kPrefix.size()) != kPrefix) return fail("is not serial:DEVICE:BAUD");
  const std::size_t last = text.rfind(':');
  if (last <= kPrefix.size() - 1) return fail("has no baud rate");
  const std::string_view device = text.substr(kPrefix.size(), last - kPrefix.size());
  const std::string_view baud = text.substr(last + 1);
  if (device.empty() || device.front() != '/') return fail("has a device that is not a path");
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(baud.data(), baud.data() + baud.size(), value);
  if (baud.empty() || ec != std::errc{} || end != baud.data() + baud.size() ||
      to_speed(value) == B0) {
    return fail("has a baud rate that is not one of 9600..1500000 (termios's standard rates)");
  }
  out.device = std::string(device);
  out.baud = value;
  return true;
}

MavlinkSerialLink::~MavlinkSerialLink() { close(); }

bool MavlinkSerialLink::open(const SerialEndpoint& endpoint, std::string& error) {
  close();
  const int fd = ::open(endpoint.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    error = endpoint.device + ": cannot open (" + std::strerror(errno) + ")";
    return false;
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    error = endpoint.device + ": not a serial port (" + std::strerror(errno) + ")";
    ::close(fd);
    return false;
  }
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  const speed_t speed = to_speed(endpoint.baud);
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &tio) != 0) {
    error = endpoint.device + ": cannot set " + std::to_string(endpoint.baud) + " baud 8N1 raw (" +
            std::strerror(errno) + ")";
    ::close(fd);
    return false;
  }
  ::tcflush(fd, TCIOFLUSH);
  fd_ = fd;
  parser_.reset();
  chunk_length_ = chunk_fed_ = 0;
  return true;
}

void MavlinkSerialLink::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

MavlinkSerialLink::Io MavlinkSerialLink::send(std::span<const std::uint8_t> frame) {
  if (fd_ < 0) return Io::error;
  int queued = 0;
  // TIOCOUTQ says what waits in the driver; a frame that may not fit is dropped whole.
  if (::ioctl(fd_, TIOCOUTQ, &queued) == 0 && queued > 4096 - static_cast<int>(frame.size())) {
    ++counters_.send_would_block;
    return Io::would_block;
  }
  std::size_t done = 0;
  while (done < frame.size()) {
    const ssize_t n = ::write(fd_, frame.data() + done, frame.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      if ((errno == EAGAIN || errno == EWOULDBLOCK) && done == 0) {
        ++counters_.send_would_block;
        return Io::would_block;
      }
      if (errno == EAGAIN || errno == EWOULDBLOCK) {
        // Finish the frame begun, waiting a few ms at most: this runs on the bus I/O thread.
        pollfd p{fd_, POLLOUT, 0};
        if (::poll(&p, 1, 5) > 0) continue;
      }
      ++counters_.send_errors;
      return Io::error;
    }
    done += static_cast<std::size_t>(n);
  }
  ++counters_.frames_out;
  return Io::ok;
}

MavlinkSerialLink::Io MavlinkSerialLink::receive(Frame& frame) {
  if (fd_ < 0) return Io::error;
  while (true) {
    if (chunk_fed_ < chunk_length_) {
      chunk_fed_ += parser_.feed(
          std::span<const std::uint8_t>(chunk_.data() + chunk_fed_, chunk_length_ - chunk_fed_));
    }
    if (parser_.next(frame)) return Io::ok;
    if (chunk_fed_ < chunk_length_) continue;
    // A stream: a frame may continue in the next read, so nothing is finished here.
    const ssize_t n = ::read(fd_, chunk_.data(), chunk_.size());
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) return Io::would_block;
      if (errno == EINTR) continue;
      ++counters_.receive_errors;
      return Io::error;
    }
    if (n == 0) return Io::would_block;  // VMIN 0: nothing there (or the peer hung up)
    counters_.bytes_in += static_cast<std::uint64_t>(n);
    chunk_length_ = static_cast<std::size_t>(n);
    chunk_fed_ = 0;
  }
}

}  // namespace rovctl::drivers::mavlink
