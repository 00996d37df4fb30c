#include "isobus/can/unix_can_bus.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "isobus/can/socketcan.hpp"

namespace spread::isobus::can {

CanFramePort connect_unix_can_bus(const std::string& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(address.sun_path)) {
    throw std::runtime_error("virtual CAN bus: socket path '" + path + "' is empty or longer than " +
                             std::to_string(sizeof(address.sun_path) - 1) + " bytes");
  }
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("virtual CAN bus: socket() failed: ") + std::strerror(errno));
  CanFramePort port(fd);  // closes the fd on a throw below
  // The port sets O_NONBLOCK; connect on a Unix socket completes or fails at once (no EINPROGRESS).
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    const int e = errno;
    std::string hint;
    if (e == ENOENT) hint = " (start `spread-canbus " + path + "` first)";
    if (e == ECONNREFUSED) hint = " (a stale socket file: nobody serves it; restart spread-canbus)";
    throw std::runtime_error("virtual CAN bus: cannot connect to '" + path + "': " + std::strerror(e) + hint);
  }
  return port;
}

CanFramePort open_can_bus(const std::string& spec) {
  if (spec.rfind(kUnixBusPrefix, 0) == 0) return connect_unix_can_bus(spec.substr(kUnixBusPrefix.size()));
  return open_socketcan(spec);
}

std::string can_bus_log_name(const std::string& spec) {
  if (spec.empty() || spec.rfind(kUnixBusPrefix, 0) == 0) return "can0";
  return spec;
}

}  // namespace spread::isobus::can
