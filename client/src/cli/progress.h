// Progress: a one-line progress bar on stderr for long streamed answers
// (done of total, rate, time left), drawn only when stderr is a terminal
// and at most ten times a second.
#ifndef FREEFORM_CLIENT_CLI_PROGRESS_H_
#define FREEFORM_CLIENT_CLI_PROGRESS_H_

#include <chrono>
#include <cstdint>
#include <string>

namespace freeform::cli {

// FormatProgress returns the bar's text for `done` of `total` `unit`s after
// `seconds`, e.g. "[=====>    ]  52%  5.2M/10M points  1.9M points/s  ETA 3s".
std::string FormatProgress(uint64_t done, uint64_t total,
                           const std::string& unit, double seconds);

class Progress {
 public:
  // Draws nothing unless `wanted` and stderr is a terminal. `total` 0 means
  // unknown (no bar, no ETA).
  Progress(bool wanted, uint64_t total, std::string unit);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Update reports that `done` units are done.
  void Update(uint64_t done);

 private:
  using Clock = std::chrono::steady_clock;

  bool shown_;
  uint64_t total_;
  std::string unit_;
  Clock::time_point start_;
  Clock::time_point drawn_;
  bool drew_ = false;
};

}  // namespace freeform::cli

#endif  // FREEFORM_CLIENT_CLI_PROGRESS_H_
