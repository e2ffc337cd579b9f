// The callers and tallies of driver.h.
#include "driver.h"

#include <algorithm>
#include <cstdlib>
#include <random>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace freeform::reliability {

std::chrono::seconds LoadSeconds() {
  const char* text = std::getenv("FREEFORM_LOAD_SECONDS");
  int seconds = 10;
  if (text != nullptr && !absl::SimpleAtoi(text, &seconds)) seconds = 10;
  return std::chrono::seconds(std::max(1, seconds));
}

uint64_t LoadSeed() {
  const char* text = std::getenv("FREEFORM_LOAD_SEED");
  uint64_t seed = 0;
  if (text != nullptr && absl::SimpleAtoi(text, &seed)) return seed;
  return std::random_device()();
}

void Tally::Add(const CallResult& result) {
  ++calls;
  std::string problem;
  if (result.status.ok()) {
    checks += result.checks;
    if (result.mismatch.empty()) {
      ++answered;
    } else {
      ++wrong;
      problem = absl::StrCat("wrong answer: ", result.mismatch);
    }
  } else if (result.chunks > 0) {
    ++cut;
    problem = absl::StrCat("stream cut after ", result.chunks,
                           " chunks: ", result.status.ToString());
  } else if (result.status.code() == absl::StatusCode::kResourceExhausted) {
    ++refused;
    if (first_refusal.empty()) first_refusal = result.status.ToString();
  } else if (result.status.code() == absl::StatusCode::kUnavailable) {
    ++unavailable;
    if (first_unavailable.empty()) {
      first_unavailable = result.status.ToString();
    }
  } else {
    ++failed;
    problem = result.status.ToString();
  }
  if (first_problem.empty()) first_problem = problem;
}

void Tally::Merge(const Tally& other) {
  calls += other.calls;
  answered += other.answered;
  checks += other.checks;
  wrong += other.wrong;
  refused += other.refused;
  unavailable += other.unavailable;
  cut += other.cut;
  failed += other.failed;
  if (first_problem.empty()) first_problem = other.first_problem;
  if (first_refusal.empty()) first_refusal = other.first_refusal;
  if (first_unavailable.empty()) first_unavailable = other.first_unavailable;
}

LoadDriver::LoadDriver(Client* client, const std::vector<RpcCase>* cases,
                       int callers, uint64_t seed)
    : client_(client), cases_(cases), callers_(callers), seed_(seed) {}

LoadDriver::~LoadDriver() { Join(); }

void LoadDriver::Start(const Run& run) {
  const auto end = std::chrono::steady_clock::now() + run.duration;
  per_caller_.assign(static_cast<size_t>(callers_),
                     std::vector<Tally>(cases_->size()));
  for (int c = 0; c < callers_; ++c) {
    threads_.emplace_back(&LoadDriver::Caller, this, c, end, run,
                          &per_caller_[c]);
  }
}

void LoadDriver::Join() {
  for (std::thread& thread : threads_) thread.join();
  threads_.clear();
  tallies_.assign(cases_->size(), Tally());
  for (const std::vector<Tally>& caller : per_caller_) {
    for (size_t k = 0; k < caller.size(); ++k) tallies_[k].Merge(caller[k]);
  }
}

void LoadDriver::Caller(int index, std::chrono::steady_clock::time_point end,
                        const Run& run, std::vector<Tally>* tallies) {
  Rng rng(seed_ + static_cast<uint64_t>(index));
  size_t next = static_cast<size_t>(index) % cases_->size();
  while (std::chrono::steady_clock::now() < end) {
    const size_t k = next;
    next = (next + 1) % cases_->size();
    ++in_flight_;
    const CallResult result = (*cases_)[k].call(*client_, rng);
    --in_flight_;
    (*tallies)[k].Add(result);
    ++finished_;
    const absl::StatusCode code = result.status.code();
    if (run.stop_on_unavailable && code == absl::StatusCode::kUnavailable) {
      return;
    }
    if (code == absl::StatusCode::kResourceExhausted) {
      std::this_thread::sleep_for(run.refusal_pause);
    }
  }
}

Tally LoadDriver::Total() const {
  Tally total;
  for (const Tally& tally : tallies_) total.Merge(tally);
  return total;
}

std::string LoadDriver::Report() const {
  std::string report =
      absl::StrFormat("requests drawn with FREEFORM_LOAD_SEED=%d\n", seed_);
  absl::StrAppend(
      &report, absl::StrFormat("%-32s %8s %8s %10s %7s %7s %5s %5s %6s\n",
                               "rpc", "calls", "answered", "checks", "refused",
                               "unavail", "cut", "wrong", "failed"));
  const auto line = [&](const std::string& name, const Tally& t) {
    absl::StrAppend(
        &report, absl::StrFormat("%-32s %8d %8d %10d %7d %7d %5d %5d %6d\n",
                                 name, t.calls, t.answered, t.checks, t.refused,
                                 t.unavailable, t.cut, t.wrong, t.failed));
  };
  for (size_t k = 0; k < tallies_.size(); ++k) {
    line((*cases_)[k].name, tallies_[k]);
  }
  const Tally total = Total();
  line("total", total);
  if (!total.first_problem.empty()) {
    absl::StrAppend(&report, "first problem: ", total.first_problem, "\n");
  }
  if (!total.first_refusal.empty()) {
    absl::StrAppend(&report, "first refusal: ", total.first_refusal, "\n");
  }
  if (!total.first_unavailable.empty()) {
    absl::StrAppend(&report, "first UNAVAILABLE: ", total.first_unavailable,
                    "\n");
  }
  return report;
}

}  // namespace freeform::reliability
