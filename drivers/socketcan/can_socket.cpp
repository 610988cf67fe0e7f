// SocketCAN I/O: struct can_frame in and out of a non-blocking descriptor, error frames decoded
// into counters and a bus-off state.
#include "drivers/socketcan/can_socket.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

namespace rovctl::drivers {

CanSocket::~CanSocket() { close(); }

CanSocket::CanSocket(CanSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      label_(std::move(other.label_)),
      bus_off_(other.bus_off_),
      last_errno_(other.last_errno_),
      counters_(other.counters_) {}

CanSocket& CanSocket::operator=(CanSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    label_ = std::move(other.label_);
    bus_off_ = other.bus_off_;
    last_errno_ = other.last_errno_;
    counters_ = other.counters_;
  }
  return *this;
}

bool CanSocket::open(const std::string& interface, std::string& error) {
  close();
  label_ = interface;
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    error = "CAN interface '" + interface + "': invalid name";
    return false;
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    error = "CAN interface '" + interface +
            "': cannot create a CAN socket: " + std::strerror(errno) +
            (errno == EAFNOSUPPORT ? " (this kernel has no SocketCAN)" : "");
    return false;
  }
  auto fail = [&](const std::string& what) {
    error = "CAN interface '" + interface + "': " + what;
    ::close(fd);
    return false;
  };
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, interface.c_str(), interface.size() + 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) != 0) {
    return fail(std::string("no such interface (") + std::strerror(errno) + ")");
  }
  const int index = ifr.ifr_ifindex;
  if (::ioctl(fd, SIOCGIFFLAGS, &ifr) != 0) {
    return fail(std::string("cannot read its flags: ") + std::strerror(errno));
  }
  if ((ifr.ifr_flags & IFF_UP) == 0) {
    return fail("interface is down (bring it up: ip link set " + interface +
                " up type can bitrate 1000000)");
  }
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) != 0) {
    return fail(std::string("cannot enable error frames: ") + std::strerror(errno));
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = index;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    return fail(std::string("cannot bind: ") + std::strerror(errno));
  }
  fd_ = fd;
  bus_off_ = false;
  return true;
}

void CanSocket::adopt(int fd, const std::string& label) {
  close();
  fd_ = fd;
  label_ = label;
  bus_off_ = false;
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}

void CanSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

CanSocket::Io CanSocket::send(const dronecan::CanFrame& frame) {
  if (fd_ < 0) return Io::error;
  can_frame cf{};
  cf.can_id = (frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG;
  cf.can_dlc = std::min<std::uint8_t>(frame.len, CAN_MAX_DLEN);
  std::memcpy(cf.data, frame.data.data(), cf.can_dlc);
  const ssize_t n = ::send(fd_, &cf, sizeof(cf), MSG_DONTWAIT | MSG_NOSIGNAL);
  if (n == static_cast<ssize_t>(sizeof(cf))) return Io::ok;
  last_errno_ = n < 0 ? errno : EMSGSIZE;
  if (last_errno_ == ENOBUFS || last_errno_ == EAGAIN) {
    ++counters_.send_queue_full;
    return Io::would_block;
  }
  ++counters_.send_errors;
  return Io::error;
}

CanSocket::Io CanSocket::receive(dronecan::CanFrame& frame) {
  if (fd_ < 0) return Io::error;
  for (;;) {
    can_frame cf{};
    const ssize_t n = ::recv(fd_, &cf, sizeof(cf), MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) return Io::would_block;
      if (errno == EINTR) continue;
      last_errno_ = errno;
      ++counters_.receive_errors;
      return Io::error;
    }
    if (n == 0) {  // the peer of an adopted stream went away
      last_errno_ = ECONNRESET;
      ++counters_.receive_errors;
      return Io::error;
    }
    if (n != static_cast<ssize_t>(sizeof(cf)) || cf.can_dlc > CAN_MAX_DLEN) {
      ++counters_.ignored_frames;
      continue;
    }
    if ((cf.can_id & CAN_ERR_FLAG) != 0) {
      ++counters_.error_frames;
      const canid_t cls = cf.can_id & CAN_ERR_MASK;
      if ((cls & CAN_ERR_BUSOFF) != 0) {
        ++counters_.bus_off_events;
        bus_off_ = true;
      }
      if ((cls & CAN_ERR_RESTARTED) != 0) {
        ++counters_.restarts;
        bus_off_ = false;
      }
      if ((cls & CAN_ERR_ACK) != 0) ++counters_.no_ack;
      if ((cls & CAN_ERR_CRTL) != 0 &&
          (cf.data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
        ++counters_.error_passive;
      }
      continue;
    }
    if ((cf.can_id & CAN_EFF_FLAG) == 0 || (cf.can_id & CAN_RTR_FLAG) != 0) {
      ++counters_.ignored_frames;  // DroneCAN uses extended data frames only
      continue;
    }
    frame.id = cf.can_id & CAN_EFF_MASK;
    frame.len = cf.can_dlc;
    std::memcpy(frame.data.data(), cf.data, cf.can_dlc);
    return Io::ok;
  }
}

}  // namespace rovctl::drivers
