// Loopback addresses and free ports for tests that run servers on several
// addresses of 127.0.0.0/8 (Linux routes all of it to lo): LoopbackAddress
// builds a socket address, FreePortOnEvery finds a port that is free on
// every given address at once, so that replicas can share it the way pods
// share a container port.
#ifndef FREEFORM_TESTS_INTEGRATION_LOOPBACK_PORTS_H_
#define FREEFORM_TESTS_INTEGRATION_LOOPBACK_PORTS_H_

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace freeform {

// LoopbackAddress returns the IPv4 socket address HOST:PORT (HOST dotted).
inline sockaddr_in LoopbackAddress(const std::string& host, int port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, host.c_str(), &address.sin_addr);
  return address;
}

// BindSocket returns a socket of `type` (SOCK_STREAM, SOCK_DGRAM) bound to
// HOST:PORT (port 0: the kernel picks), or -1 when the bind fails.
inline int BindSocket(const std::string& host, int port, int type) {
  const int socket_fd = socket(AF_INET, type, 0);
  if (socket_fd < 0) return -1;
  const sockaddr_in address = LoopbackAddress(host, port);
  if (bind(socket_fd, reinterpret_cast<const sockaddr*>(&address),
           sizeof(address)) != 0) {
    close(socket_fd);
    return -1;
  }
  return socket_fd;
}

// FreePortOnEvery returns a port that every socket type of `types` can bind
// on every host of `hosts` right now (the kernel picks it for the first
// pair; the others are tried on it). The sockets are closed again before
// it returns, so a busy machine may take the port in between: callers
// retry. UNAVAILABLE after 50 picks.
inline absl::StatusOr<int> FreePortOnEvery(
    const std::vector<std::string>& hosts, const std::vector<int>& types) {
  for (int pick = 0; pick < 50; ++pick) {
    const int first = BindSocket(hosts.front(), 0, types.front());
    if (first < 0) break;
    sockaddr_in bound{};
    socklen_t length = sizeof(bound);
    getsockname(first, reinterpret_cast<sockaddr*>(&bound), &length);
    const int port = ntohs(bound.sin_port);
    std::vector<int> sockets = {first};
    bool free_everywhere = true;
    for (const std::string& host : hosts) {
      for (const int type : types) {
        if (host == hosts.front() && type == types.front()) continue;
        const int socket_fd = BindSocket(host, port, type);
        free_everywhere = free_everywhere && socket_fd >= 0;
        if (socket_fd >= 0) sockets.push_back(socket_fd);
      }
    }
    for (const int socket_fd : sockets) close(socket_fd);
    if (free_everywhere) return port;
  }
  return absl::UnavailableError(absl::StrCat("no port is free on every one of ",
                                             absl::StrJoin(hosts, ", ")));
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_INTEGRATION_LOOPBACK_PORTS_H_
