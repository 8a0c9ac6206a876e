// ThreadTuner: the thread count of a run with threads = auto.
//
// On a machine where other programs run, OpenMP threads spin at every
// barrier while a partner is descheduled, and 2 threads can be many times
// slower than 1. So the count is measured, not assumed: it starts from the
// cores this process may use (its CPU affinity) less the load average, then
// times a few steps with each candidate count (that one, half of it, ... 1)
// and keeps the fastest; every `retrialSeconds` of stepping it times the
// candidates again, since the load changes. A count is kept unless another
// is at least 5% faster. Results do not depend on the count (the loops are
// in gather form), so switching never changes the answer.
//
// Tiny scenes (every loop serial) use one thread and are not timed.
#pragma once

#include "sph/types.hpp"

#include <omp.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

namespace sph {

class ThreadTuner {
 public:
  // `cores`: the largest count to consider (0: this process's CPUs).
  explicit ThreadTuner(std::size_t particles, int cores = 0, double retrialSeconds = 20)
      : retrial_(retrialSeconds) {
    const int usable = cores > 0 ? cores : usableCores();
    if (particles < kMinParallelSize || usable <= 1) {
      candidates_ = {1};
    } else {
      for (int t = usable; t >= 1; t /= 2) candidates_.push_back(t);
      if (candidates_.back() != 1) candidates_.push_back(1);
    }
    // Start at the free cores: the usable ones less the load of the others.
    const int free = std::clamp(static_cast<int>(std::lround(usable - loadAverage())), 1, usable);
    best_ = candidates_.front();
    for (int t : candidates_)
      if (t <= free) {
        best_ = t;
        break;
      }
    startTrial();
  }

  // A count chosen by the user: recorded, never changed.
  static ThreadTuner fixed(int threads) {
    ThreadTuner t;
    t.candidates_ = {threads};
    t.best_ = t.current_ = threads;
    t.history_ = {threads};
    return t;
  }

  int threads() const { return current_; }
  bool tuning() const { return candidates_.size() > 1; }
  // Every count used so far, in order (for run.json).
  const std::vector<int>& history() const { return history_; }

  // After each step: its stepping time. May change the thread count.
  void record(double seconds) {
    if (!tuning()) return;
    if (trial_ < 0) {  // running with the best count
      sinceTrial_ += seconds;
      if (sinceTrial_ >= retrial_) startTrial();
      return;
    }
    if (skip_ > 0) {  // the first step after a change warms caches and buffers
      --skip_;
      return;
    }
    samples_.push_back(seconds);
    if (samples_.size() < kSamples) return;
    std::nth_element(samples_.begin(), samples_.begin() + kSamples / 2, samples_.end());
    times_[static_cast<std::size_t>(trial_)] = samples_[kSamples / 2];
    samples_.clear();
    if (++trial_ < static_cast<int>(order_.size())) {
      use(order_[static_cast<std::size_t>(trial_)]);
      return;
    }
    // Decide: the fastest, unless the present best (timed first) is within
    // 5% of it.
    std::size_t fastest = 0;
    for (std::size_t k = 0; k < order_.size(); ++k)
      if (times_[k] < times_[fastest]) fastest = k;
    if (times_[fastest] < 0.95 * times_[0]) best_ = order_[fastest];
    trial_ = -1;
    sinceTrial_ = 0;
    use(best_);
  }

  static int usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
    return std::max(1, omp_get_num_procs());
  }

  static double loadAverage() {
    std::ifstream in("/proc/loadavg");
    double l = 0;
    in >> l;
    return in ? l : 0;
  }

 private:
  ThreadTuner() : retrial_(0) {}
  static constexpr std::size_t kSamples = 5;

  // Time the present best first, then the other candidates.
  void startTrial() {
    order_ = {best_};
    for (int t : candidates_)
      if (t != best_) order_.push_back(t);
    trial_ = 0;
    times_.assign(order_.size(), 0);
    samples_.clear();
    use(best_);
  }

  void use(int t) {
    current_ = t;
    omp_set_num_threads(t);
    skip_ = 1;
    if (history_.empty() || history_.back() != t) history_.push_back(t);
  }

  double retrial_;
  std::vector<int> candidates_;  // counts to time, largest first
  std::vector<int> order_;       // the order of the present trial (best first)
  std::vector<double> times_;    // median step time of each in order_
  std::vector<double> samples_;
  int best_ = 1, current_ = 1;
  int trial_ = -1;               // candidate being timed; -1: running with best_
  int skip_ = 0;
  double sinceTrial_ = 0;
  std::vector<int> history_;
};

}  // namespace sph
