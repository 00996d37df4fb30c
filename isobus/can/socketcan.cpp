#include "isobus/can/socketcan.hpp"

#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace spread::isobus::can {

bool socketcan_available() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

CanFramePort open_socketcan(const std::string& interface_name) {
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ) {
    throw std::runtime_error("SocketCAN: interface name '" + interface_name + "' is empty or too long");
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    const int e = errno;
    if (e == EAFNOSUPPORT) {
      throw std::runtime_error("SocketCAN: this kernel has no AF_CAN support (load the can and can_raw modules)");
    }
    throw std::runtime_error(std::string("SocketCAN: socket(PF_CAN, SOCK_RAW, CAN_RAW) failed: ") + std::strerror(e));
  }
  CanFramePort port(fd);  // owns the fd from here: closed on any throw below
  const unsigned index = ::if_nametoindex(interface_name.c_str());
  if (index == 0) {
    throw std::runtime_error("SocketCAN: no network interface '" + interface_name +
                             "' (ip link add / ip link set " + interface_name + " up)");
  }
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    throw std::runtime_error("SocketCAN: bind to '" + interface_name + "' failed: " + std::strerror(errno));
  }
  return port;
}

}  // namespace spread::isobus::can
