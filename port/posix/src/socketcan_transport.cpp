#include "cvtplant/port/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "cvtplant/port/posix_clock.hpp"

namespace cvt::port {

static_assert(can_err::kBusOff == CAN_ERR_BUSOFF && can_err::kController == CAN_ERR_CRTL &&
                  can_err::kRestarted == CAN_ERR_RESTARTED && can_err::kCtrlTxPassive == CAN_ERR_CRTL_TX_PASSIVE &&
                  can_err::kCtrlActive == CAN_ERR_CRTL_ACTIVE,
              "error-class bits must match linux/can/error.h");

SocketCanTransport::~SocketCanTransport() { close(); }

void SocketCanTransport::fail(const char* step, int err) noexcept {
  last_errno_ = err;
  std::snprintf(error_, sizeof error_, "%s: %s", step, std::strerror(err));
}

int SocketCanTransport::open(const char* ifname, const SocketCanConfig& cfg) noexcept {
  close();
  cfg_ = cfg;
  error_[0] = '\0';
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    fail("socket(AF_CAN)", errno);
    return last_errno_;
  }
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  const int one = 1;
  const int own = cfg.receive_own_messages ? 1 : 0;
  ifreq ifr{};
  if (std::strlen(ifname) >= sizeof ifr.ifr_name) {
    ::close(fd);
    fail("interface name", ENAMETOOLONG);
    return last_errno_;
  }
  std::strncpy(ifr.ifr_name, ifname, sizeof ifr.ifr_name - 1);
  const char* step = nullptr;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) {
    step = "setsockopt(CAN_RAW_ERR_FILTER)";
  } else if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof own) < 0) {
    step = "setsockopt(CAN_RAW_RECV_OWN_MSGS)";
  } else if (::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) < 0) {
    step = "setsockopt(SO_RXQ_OVFL)";
  } else if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
    step = "ioctl(SIOCGIFINDEX)";
  } else {
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) step = "bind";
  }
  if (step) {
    const int err = errno;
    ::close(fd);
    fail(step, err);
    return err;
  }
  fd_ = fd;
  state_ = CanBusState::ErrorActive;
  return 0;
}

void SocketCanTransport::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

CanIoStatus SocketCanTransport::send(const can::CanFrame& f) noexcept {
  const bool ext = (f.flags & can::kFrameExtendedId) != 0;
  if (fd_ < 0) return CanIoStatus::IoError;
  if (f.dlc > CAN_MAX_DLEN || (f.flags & can::kFrameError) ||
      f.id > (ext ? can::kExtIdMask : can::kStdIdMask)) {
    ++counters_.tx_invalid;
    return CanIoStatus::InvalidFrame;
  }
  if (state_ == CanBusState::BusOff) return CanIoStatus::BusOff;
  can_frame cf{};
  cf.can_id = f.id | (ext ? CAN_EFF_FLAG : 0u) | ((f.flags & can::kFrameRemote) ? CAN_RTR_FLAG : 0u);
  cf.can_dlc = f.dlc;
  std::memcpy(cf.data, f.data, f.dlc);
  for (uint32_t attempt = 0;; ++attempt) {
    const ssize_t n = ::write(fd_, &cf, sizeof cf);
    if (n == static_cast<ssize_t>(sizeof cf)) {
      ++counters_.tx_frames;
      return CanIoStatus::Ok;
    }
    const int err = n < 0 ? errno : EIO;
    if (err == EINTR) continue;
    if (err != ENOBUFS && err != EAGAIN) {
      last_errno_ = err;
      if (err == EINVAL) {
        ++counters_.tx_invalid;
        return CanIoStatus::InvalidFrame;
      }
      return CanIoStatus::IoError;
    }
    if (attempt == cfg_.enobufs_retries) {
      ++counters_.tx_dropped;
      return CanIoStatus::Dropped;
    }
    ++counters_.tx_enobufs_retries;
    timespec ts{0, static_cast<long>(cfg_.enobufs_backoff_ns)};
    ::nanosleep(&ts, nullptr);
  }
}

CanIoStatus SocketCanTransport::receive(can::CanFrame& out, int64_t timeout_ns) noexcept {
  if (fd_ < 0) return CanIoStatus::IoError;
  PosixMonotonicClock clock;
  const int64_t deadline = timeout_ns > 0 ? clock.now_ns() + timeout_ns : 0;
  for (;;) {
    can_frame cf{};
    iovec iov{&cf, sizeof cf};
    alignas(cmsghdr) char ctrl[CMSG_SPACE(sizeof(uint32_t))];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = ctrl;
    msg.msg_controllen = sizeof ctrl;
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      const int err = errno;
      if (err == EINTR) continue;
      if (err != EAGAIN && err != EWOULDBLOCK) {
        last_errno_ = err;
        return CanIoStatus::IoError;
      }
      const int64_t left = timeout_ns > 0 ? deadline - clock.now_ns() : 0;
      if (left <= 0) return CanIoStatus::Timeout;
      pollfd p{fd_, POLLIN, 0};
      timespec ts{static_cast<time_t>(left / 1000000000), static_cast<long>(left % 1000000000)};
      ::ppoll(&p, 1, &ts, nullptr);
      continue;
    }
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        uint32_t drops = 0;
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        // Cumulative per socket; modular difference survives the u32 wrap.
        counters_.rx_kernel_drops += static_cast<uint32_t>(drops - kernel_drops_seen_);
        kernel_drops_seen_ = drops;
      }
    }
    if (n != static_cast<ssize_t>(sizeof cf) || cf.can_dlc > CAN_MAX_DLEN) {
      ++counters_.rx_invalid;  // FD-sized or malformed: not a classic frame
      continue;
    }
    out = can::CanFrame{};
    out.dlc = cf.can_dlc;
    std::memcpy(out.data, cf.data, cf.can_dlc);
    if (cf.can_id & CAN_ERR_FLAG) {
      out.flags = can::kFrameError;
      out.id = cf.can_id & CAN_ERR_MASK;
      ++counters_.rx_error_frames;
      const CanBusState next = next_bus_state(state_, out);
      if (next == CanBusState::BusOff && state_ != CanBusState::BusOff) ++counters_.bus_off_events;
      state_ = next;
      return CanIoStatus::ErrorFrame;
    }
    if (cf.can_id & CAN_EFF_FLAG) {
      out.flags |= can::kFrameExtendedId;
      out.id = cf.can_id & CAN_EFF_MASK;
    } else {
      out.id = cf.can_id & CAN_SFF_MASK;
    }
    // Remote frames are passed up flagged; the message decoder refuses them
    // (NotDataFrame) so the receiver counts them with its other rejections.
    if (cf.can_id & CAN_RTR_FLAG) out.flags |= can::kFrameRemote;
    ++counters_.rx_frames;
    return CanIoStatus::Ok;
  }
}

}  // namespace cvt::port
