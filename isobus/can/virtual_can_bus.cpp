#include "isobus/can/virtual_can_bus.hpp"

#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace spread::isobus::can {

std::pair<CanFramePort, CanFramePort> make_virtual_can_pair() {
  int fds[2] = {-1, -1};
  if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, fds) != 0) {
    throw std::runtime_error(std::string("virtual CAN bus: socketpair(AF_UNIX, SOCK_SEQPACKET) failed: ") +
                             std::strerror(errno));
  }
  return {CanFramePort(fds[0]), CanFramePort(fds[1])};
}

}  // namespace spread::isobus::can
