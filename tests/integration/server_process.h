// ServerProcess: a freeformd child process listening on 127.0.0.1 with a
// kernel-chosen port, for the integration and reliability tests. The
// constructor starts it and reads the port it prints (and, with a
// --metrics_listen flag, the metrics port it prints next, with an
// --http_listen flag the HTTP gateway's port after those); the destructor
// kills it if it still runs. Its log (stderr) can go to a file, and its
// resident memory is read from /proc.
#ifndef FREEFORM_TESTS_INTEGRATION_SERVER_PROCESS_H_
#define FREEFORM_TESTS_INTEGRATION_SERVER_PROCESS_H_

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"

namespace freeform {

class ServerProcess {
 public:
  // Runs freeformd with --threads=2 and --grace_period=5s; `extra_flags`
  // come after those, so they may override them (--listen=127.0.0.1:PORT
  // restarts a replica on its port). With `log_path` the log is appended to
  // that file instead of the test's stderr.
  explicit ServerProcess(std::vector<std::string> extra_flags = {},
                         const std::string& log_path = "") {
    std::vector<std::string> arguments = {FREEFORMD_PATH,
                                          "--listen=127.0.0.1:0", "--threads=2",
                                          "--grace_period=5s"};
    arguments.insert(arguments.end(), extra_flags.begin(), extra_flags.end());
    int out[2];
    EXPECT_EQ(pipe(out), 0);
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      if (!log_path.empty()) {
        const int log =
            open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (log < 0) _exit(126);
        dup2(log, STDERR_FILENO);
        close(log);
      }
      std::vector<char*> argv;
      for (std::string& argument : arguments) argv.push_back(argument.data());
      argv.push_back(nullptr);
      execv(FREEFORMD_PATH, argv.data());
      _exit(127);
    }
    close(out[1]);
    stdout_ = fdopen(out[0], "r");
    port_ = ReadPort("freeformd listening on ");
    for (const std::string& flag : extra_flags) {
      if (flag.rfind("--metrics_listen=", 0) == 0 &&
          flag != "--metrics_listen=") {
        metrics_port_ = ReadPort("freeformd metrics on ");
      }
    }
    for (const std::string& flag : extra_flags) {
      if (flag.rfind("--http_listen=", 0) == 0 && flag != "--http_listen=") {
        http_port_ = ReadPort("freeformd http listening on ");
      }
    }
  }
  ~ServerProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (stdout_ != nullptr) fclose(stdout_);
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  int port() const { return port_; }
  // metrics_port returns the port of the metrics, 0 without them.
  int metrics_port() const { return metrics_port_; }
  // http_port returns the port of the HTTP gateway, 0 without it.
  int http_port() const { return http_port_; }
  pid_t pid() const { return pid_; }
  std::string address() const { return absl::StrCat("127.0.0.1:", port_); }

  // announced returns the lines read from the server's stdout so far.
  const std::vector<std::string>& announced() const { return announced_; }
  // Signal sends `signal` to the process.
  void Signal(int signal) { kill(pid_, signal); }

  // WaitForExit returns the exit status (128 + the signal when killed by
  // one), or nullopt when the process still runs after `timeout`.
  std::optional<int> WaitForExit(std::chrono::milliseconds timeout) {
    const auto give_up = std::chrono::steady_clock::now() + timeout;
    while (true) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      if (std::chrono::steady_clock::now() >= give_up) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  // ResidentKiB returns a memory figure of /proc/PID/status in KiB: VmRSS
  // (resident now) or VmHWM (peak resident); -1 when it cannot be read.
  long ResidentKiB(const std::string& field = "VmRSS") const {
    std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
    std::string line;
    while (std::getline(status, line)) {
      if (line.rfind(field + ":", 0) == 0) {
        return std::stol(line.substr(field.size() + 1));
      }
    }
    return -1;
  }

  // Sends `signal` and returns the exit status (or -1 after `timeout`).
  int StopWith(int signal, std::chrono::seconds timeout) {
    Signal(signal);
    return WaitForExit(timeout).value_or(-1);
  }

 private:
  // ReadPort reads the next line of the server's stdout (announced()) and
  // returns the port of the HOST:PORT that follows `prefix` in it (the line
  // itself with --log_format=text, its message with json), or 0.
  int ReadPort(const std::string& prefix) {
    std::array<char, 256> line{};
    if (fgets(line.data(), line.size(), stdout_) == nullptr) return 0;
    announced_.emplace_back(line.data());
    const std::string& text = announced_.back();
    const size_t start = text.find(prefix);
    if (start == std::string::npos) return 0;
    std::string address = text.substr(start + prefix.size());
    address = address.substr(0, address.find_first_of("\" \n"));
    const size_t colon = address.rfind(':');
    if (colon == std::string::npos) return 0;
    return std::atoi(address.c_str() + colon + 1);
  }

  pid_t pid_ = -1;
  FILE* stdout_ = nullptr;
  std::vector<std::string> announced_;
  int port_ = 0;
  int metrics_port_ = 0;
  int http_port_ = 0;
  bool exited_ = false;
};

}  // namespace freeform

#endif  // FREEFORM_TESTS_INTEGRATION_SERVER_PROCESS_H_
