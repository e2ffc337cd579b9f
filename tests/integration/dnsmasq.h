// Dnsmasq: a dnsmasq child process that answers A queries for one name from
// a hosts file, on a free port of 127.0.0.1, for the scale-out test: the
// loopback stand-in for a Kubernetes headless Service, whose records follow
// the ready pods. SetAddresses rewrites the file and makes dnsmasq re-read
// it (SIGHUP), then waits until a query sees the new records; Resolve asks
// it (a minimal DNS client over UDP). The destructor stops the process and
// removes its files. Not thread-safe.
//
// dnsmasq runs in the foreground with no configuration file, no upstream
// servers, /etc/hosts unread, no pid file and its log in its folder: the
// machine's resolver and port 53 stay untouched (Debian's dnsmasq-base has
// the binary without the system service).
#ifndef FREEFORM_TESTS_INTEGRATION_DNSMASQ_H_
#define FREEFORM_TESTS_INTEGRATION_DNSMASQ_H_

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"
#include "loopback_ports.h"

namespace freeform {

namespace dns_internal {

constexpr uint16_t kTypeA = 1;
constexpr uint16_t kClassInternet = 1;

inline void AppendUint16(std::string& message, uint16_t value) {
  message.push_back(static_cast<char>(value >> 8));
  message.push_back(static_cast<char>(value & 0xFF));
}

inline uint16_t ReadUint16(absl::string_view message, size_t offset) {
  return static_cast<uint16_t>((static_cast<uint8_t>(message[offset]) << 8) |
                               static_cast<uint8_t>(message[offset + 1]));
}

// AQuery returns a DNS query (RFC 1035 4.1) for the A records of `name`,
// recursion desired.
inline std::string AQuery(absl::string_view name, uint16_t id) {
  std::string query;
  AppendUint16(query, id);
  AppendUint16(query, 0x0100);  // a standard query, recursion desired
  AppendUint16(query, 1);       // one question; no answer or other record
  for (int section = 0; section < 3; ++section) AppendUint16(query, 0);
  for (absl::string_view label : absl::StrSplit(name, '.')) {
    query.push_back(static_cast<char>(label.size()));
    query.append(label.data(), label.size());
  }
  query.push_back('\0');
  AppendUint16(query, kTypeA);
  AppendUint16(query, kClassInternet);
  return query;
}

// SkipName returns the offset after the name at `offset` (labels, ending
// in a zero length or a compression pointer), or npos past the end.
inline size_t SkipName(absl::string_view message, size_t offset) {
  while (offset < message.size()) {
    const auto length = static_cast<uint8_t>(message[offset]);
    if ((length & 0xC0) == 0xC0) return offset + 2;
    if (length == 0) return offset + 1;
    offset += 1 + length;
  }
  return absl::string_view::npos;
}

// AnswerAddresses returns the dotted IPv4 addresses of the A records in the
// answer section of `answer`, sorted; DATA_LOSS when it is cut short.
inline absl::StatusOr<std::vector<std::string>> AnswerAddresses(
    absl::string_view answer) {
  if (answer.size() < 12) return absl::DataLossError("short DNS header");
  const uint16_t answers = ReadUint16(answer, 6);
  size_t offset = SkipName(answer, 12);  // the one question
  if (offset != absl::string_view::npos) offset += 4;
  std::vector<std::string> addresses;
  for (uint16_t i = 0; i < answers; ++i) {
    offset = SkipName(answer, offset);
    if (offset == absl::string_view::npos || offset + 10 > answer.size()) {
      return absl::DataLossError("DNS answer cut short");
    }
    const uint16_t type = ReadUint16(answer, offset);
    const uint16_t length = ReadUint16(answer, offset + 8);
    offset += 10;
    if (offset + length > answer.size()) {
      return absl::DataLossError("DNS record cut short");
    }
    if (type == kTypeA && length == 4) {
      std::array<char, INET_ADDRSTRLEN> text{};
      inet_ntop(AF_INET, answer.data() + offset, text.data(), text.size());
      addresses.emplace_back(text.data());
    }
    offset += length;
  }
  std::sort(addresses.begin(), addresses.end());
  return addresses;
}

}  // namespace dns_internal

// QueryAddresses asks the DNS server on 127.0.0.1:`port` for the A records
// of `name` and returns their addresses, sorted; UNAVAILABLE when no answer
// comes within a second.
inline absl::StatusOr<std::vector<std::string>> QueryAddresses(
    int port, absl::string_view name) {
  const int socket_fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_fd < 0) return absl::InternalError("no UDP socket");
  const timeval timeout = {.tv_sec = 1, .tv_usec = 0};
  setsockopt(socket_fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  const sockaddr_in server = LoopbackAddress("127.0.0.1", port);
  const std::string query = dns_internal::AQuery(name, 0x5eed);
  std::array<char, 1500> answer{};
  ssize_t received = -1;
  if (sendto(socket_fd, query.data(), query.size(), 0,
             reinterpret_cast<const sockaddr*>(&server),
             sizeof(server)) == static_cast<ssize_t>(query.size())) {
    received = recv(socket_fd, answer.data(), answer.size(), 0);
  }
  close(socket_fd);
  if (received < 0) {
    return absl::UnavailableError(
        absl::StrCat("no DNS answer from 127.0.0.1:", port, " for ", name));
  }
  return dns_internal::AnswerAddresses(
      absl::string_view(answer.data(), static_cast<size_t>(received)));
}

class Dnsmasq {
 public:
  // Binary returns the path of dnsmasq, or "" when it is not installed
  // (dnsmasq-base puts it in /usr/sbin, which a user's PATH may lack).
  static std::string Binary() {
    std::vector<std::string> candidates = {"/usr/sbin/dnsmasq"};
    if (const char* path = std::getenv("PATH"); path != nullptr) {
      for (absl::string_view folder : absl::StrSplit(path, ':')) {
        candidates.push_back(absl::StrCat(folder, "/dnsmasq"));
      }
    }
    for (const std::string& candidate : candidates) {
      if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return "";
  }

  // Start serves `name` (which it alone answers: no query goes upstream)
  // with the A records `addresses`, and returns once a query sees them.
  static absl::StatusOr<std::unique_ptr<Dnsmasq>> Start(
      const std::string& name, const std::vector<std::string>& addresses) {
    std::string folder = "/tmp/freeform_dnsmasq_XXXXXX";
    if (mkdtemp(folder.data()) == nullptr) {
      return absl::InternalError("cannot make a temporary folder");
    }
    // dnsmasq started as root reads the hosts file as its own user.
    chmod(folder.c_str(), 0755);
    std::unique_ptr<Dnsmasq> server(new Dnsmasq(name, folder));
    if (absl::Status status = server->WriteHosts(addresses); !status.ok()) {
      return status;
    }
    // A port found free may be taken before dnsmasq binds it: try others.
    for (int attempt = 0; attempt < 5; ++attempt) {
      absl::StatusOr<int> port =
          FreePortOnEvery({"127.0.0.1"}, {SOCK_DGRAM, SOCK_STREAM});
      if (!port.ok()) return port.status();
      server->Spawn(*port);
      if (server->WaitFor(addresses).ok()) return server;
      server->Stop();
    }
    return absl::UnavailableError(
        absl::StrCat("dnsmasq did not serve; its log: ", server->Log()));
  }

  ~Dnsmasq() {
    Stop();
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  Dnsmasq(const Dnsmasq&) = delete;
  Dnsmasq& operator=(const Dnsmasq&) = delete;

  int port() const { return port_; }

  // SetAddresses makes `addresses` the name's A records and returns once
  // dnsmasq answers with them (DEADLINE_EXCEEDED after 5 s).
  absl::Status SetAddresses(const std::vector<std::string>& addresses) {
    if (absl::Status status = WriteHosts(addresses); !status.ok()) {
      return status;
    }
    kill(pid_, SIGHUP);  // dnsmasq re-reads its hosts files
    return WaitFor(addresses);
  }

  // Resolve returns the name's A records as dnsmasq answers them now.
  absl::StatusOr<std::vector<std::string>> Resolve() const {
    return QueryAddresses(port_, name_);
  }

 private:
  Dnsmasq(std::string name, std::string folder)
      : name_(std::move(name)), folder_(std::move(folder)) {}

  std::string HostsPath() const { return folder_ + "/hosts"; }
  std::string LogPath() const { return folder_ + "/dnsmasq.log"; }

  std::string Log() const {
    std::ifstream file(LogPath());
    return std::string(std::istreambuf_iterator<char>(file), {});
  }

  // WriteHosts replaces the hosts file at once (a rename), so that dnsmasq
  // never reads half of it.
  absl::Status WriteHosts(const std::vector<std::string>& addresses) const {
    const std::string staged = HostsPath() + ".new";
    {
      std::ofstream file(staged, std::ios::trunc);
      for (const std::string& address : addresses) {
        file << address << " " << name_ << "\n";
      }
      if (!file) return absl::InternalError("cannot write " + staged);
    }
    if (std::rename(staged.c_str(), HostsPath().c_str()) != 0) {
      return absl::InternalError("cannot rename " + staged);
    }
    return absl::OkStatus();
  }

  // Spawn starts dnsmasq on 127.0.0.1:`port`, its stderr to the log.
  void Spawn(int port) {
    port_ = port;
    std::vector<std::string> arguments = {Binary(),
                                          "--keep-in-foreground",
                                          "--conf-file=/dev/null",
                                          absl::StrCat("--port=", port),
                                          "--listen-address=127.0.0.1",
                                          "--bind-interfaces",
                                          "--no-resolv",
                                          "--no-hosts",
                                          "--addn-hosts=" + HostsPath(),
                                          absl::StrCat("--local=/", name_, "/"),
                                          "--pid-file=",
                                          "--log-facility=" + LogPath()};
    // As root it would run as the user `dnsmasq`, which may not exist.
    if (geteuid() == 0) arguments.push_back("--user=root");
    // Everything the child needs is made before fork: between fork and
    // exec it may only make system calls (the test has other threads).
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    const std::string log_path = LogPath();
    pid_ = fork();
    if (pid_ == 0) {
      // dnsmasq ends with the test even when the test crashes.
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      const int log =
          open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (log >= 0) dup2(log, STDERR_FILENO);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }

  // WaitFor polls until dnsmasq answers with `addresses` (sorted as
  // Resolve returns them); UNAVAILABLE when it exited, DEADLINE_EXCEEDED
  // after 5 s.
  absl::Status WaitFor(std::vector<std::string> addresses) {
    std::sort(addresses.begin(), addresses.end());
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::seconds(5);
    absl::StatusOr<std::vector<std::string>> seen;
    while (std::chrono::steady_clock::now() < give_up) {
      if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return absl::UnavailableError("dnsmasq exited: " + Log());
      }
      seen = Resolve();
      if (seen.ok() && *seen == addresses) return absl::OkStatus();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return absl::DeadlineExceededError(absl::StrCat(
        "dnsmasq answers ",
        seen.ok() ? absl::StrJoin(*seen, ",") : seen.status().ToString(),
        ", not ", absl::StrJoin(addresses, ",")));
  }

  void Stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

  const std::string name_;
  const std::string folder_;
  pid_t pid_ = -1;
  int port_ = 0;
};

}  // namespace freeform

#endif  // FREEFORM_TESTS_INTEGRATION_DNSMASQ_H_
