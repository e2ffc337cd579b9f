// The progress bar (progress.h).
#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace freeform::cli {
namespace {

constexpr int kBarWidth = 24;
constexpr auto kRedrawEvery = std::chrono::milliseconds(100);

// 1234567 -> "1.2M".
std::string Short(double value) {
  if (value >= 1e9) return absl::StrFormat("%.1fG", value / 1e9);
  if (value >= 1e6) return absl::StrFormat("%.1fM", value / 1e6);
  if (value >= 1e4) return absl::StrFormat("%.1fk", value / 1e3);
  return absl::StrFormat("%.0f", value);
}

// 75 -> "1m15s".
std::string Duration(double seconds) {
  const auto whole = static_cast<int64_t>(std::ceil(seconds));
  if (whole < 60) return absl::StrCat(whole, "s");
  if (whole < 3600) return absl::StrCat(whole / 60, "m", whole % 60, "s");
  return absl::StrCat(whole / 3600, "h", whole % 3600 / 60, "m");
}

}  // namespace

std::string FormatProgress(uint64_t done, uint64_t total,
                           const std::string& unit, double seconds) {
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0;
  const std::string rate_text =
      rate > 0 ? absl::StrCat("  ", Short(rate), " ", unit, "/s") : "";
  if (total == 0) {
    return absl::StrCat(Short(static_cast<double>(done)), " ", unit, rate_text);
  }
  const double fraction =
      std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(static_cast<size_t>(filled), '=');
  if (filled < kBarWidth) bar += '>';
  bar.resize(kBarWidth, ' ');
  std::string eta;
  if (rate > 0 && done < total) {
    eta = absl::StrCat("  ETA ",
                       Duration(static_cast<double>(total - done) / rate));
  }
  return absl::StrFormat(
      "[%s] %3d%%  %s/%s %s%s%s", bar, static_cast<int>(fraction * 100),
      Short(static_cast<double>(done)), Short(static_cast<double>(total)), unit,
      rate_text, eta);
}

Progress::Progress(bool wanted, uint64_t total, std::string unit)
    : shown_(wanted && isatty(STDERR_FILENO)),
      total_(total),
      unit_(std::move(unit)),
      start_(Clock::now()),
      drawn_(start_) {}

Progress::~Progress() {
  // Clear the line so that what follows on stderr starts clean.
  if (drew_) std::fputs("\r\033[K", stderr);
}

void Progress::Update(uint64_t done) {
  if (!shown_) return;
  const Clock::time_point now = Clock::now();
  const bool last = total_ > 0 && done >= total_;
  if (now - drawn_ < kRedrawEvery && !last) return;
  drawn_ = now;
  drew_ = true;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[K%s",
               FormatProgress(done, total_, unit_, seconds).c_str());
  std::fflush(stderr);
}

}  // namespace freeform::cli
