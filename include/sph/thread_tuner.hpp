// ThreadTuner: the thread count of a run with threads = auto.
//
// On a machine where other programs run, OpenMP threads wait at every
// barrier while a partner is descheduled, and 2 threads can be many times
// slower than 1. So the count is measured, not assumed: it starts from the
// cores this process may use (its CPU affinity) less the load average, then
// times each candidate count (that one, half of it, ... 1) in turn, in
// slices of at least `sliceSeconds` of stepping, `rounds` times round (so
// that a change of load during the trial hits every candidate alike; a
// count twice as slow as the present best is not timed again), and
// keeps the fastest by mean step time: throughput is total time, and the
// rare very slow step of an oversubscribed team is what a median would
// hide. A count is kept unless another is at least 5% faster. The
// candidates are timed again every `retrialSeconds` of stepping, and at
// once when the steps become `slowdown` times slower than measured (a
// competing program started). Results do not depend on the count (the
// loops are in gather form), so switching never changes the answer.
//
// Tiny scenes (every loop serial) use one thread and are not timed.
#pragma once

#include "sph/types.hpp"

#include <omp.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <map>
#include <vector>

namespace sph {

struct ThreadTunerSettings {
  double sliceSeconds = 0.1;    // stepping time per candidate and round
  int rounds = 2;               // times round the candidates per trial
  double retrialSeconds = 20;   // stepping time between trials
  double slowdown = 1.5;        // steps this much slower than measured: retrial
};

class ThreadTuner {
 public:
  using Settings = ThreadTunerSettings;

  // `cores`: the largest count to consider (0: this process's CPUs);
  // `load`: the load of the other programs (< 0: the load average).
  explicit ThreadTuner(std::size_t particles, int cores = 0, double load = -1, Settings settings = Settings())
      : settings_(settings) {
    const int usable = cores > 0 ? cores : usableCores();
    if (particles < kMinParallelSize || usable <= 1) {
      candidates_ = {1};
    } else {
      for (int t = usable; t >= 1; t /= 2) candidates_.push_back(t);
      if (candidates_.back() != 1) candidates_.push_back(1);
    }
    // Start at the free cores: the usable ones less the load of the others.
    const double others = load >= 0 ? load : loadAverage();
    const int free = std::clamp(static_cast<int>(std::lround(usable - others)), 1, usable);
    best_ = candidates_.back();
    for (int t : candidates_)
      if (t <= free) {
        best_ = t;
        break;
      }
    if (tuning()) startTrial();
    else use(best_);
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
  // Every count used so far, once each, in the order first used (run.json).
  const std::vector<int>& history() const { return history_; }
  // Stepping time with each count.
  const std::map<int, double>& secondsWith() const { return secondsWith_; }

  // After each step: its stepping time. May change the thread count.
  void record(double seconds) {
    secondsWith_[current_] += seconds;
    if (!tuning()) return;
    if (trial_ < 0) {
      running(seconds);
      return;
    }
    if (skip_) {  // the first step after a change warms caches and buffers
      skip_ = false;
      return;
    }
    const std::size_t k = static_cast<std::size_t>(trial_) % order_.size();
    time_[k] += seconds;
    ++steps_[k];
    sliceTime_ += seconds;
    ++sliceSteps_;
    if (sliceTime_ < settings_.sliceSeconds || sliceSteps_ < kMinSliceSteps) return;
    // A count more than twice as slow as the present best is out of the
    // remaining rounds: beside a competing program 2 threads can be 20
    // times slower, and timing them again would cost more than it tells.
    if (k > 0 && perStep(k) > kLoser * perStep(0)) out_[k] = true;
    const int slices = static_cast<int>(order_.size()) * settings_.rounds;
    while (++trial_ < slices && out_[static_cast<std::size_t>(trial_) % order_.size()]) {}
    if (trial_ < slices) {
      startSlice(order_[static_cast<std::size_t>(trial_) % order_.size()]);
      return;
    }
    // Decide: the fastest mean step, unless the present best (first in
    // order_) is within 5% of it.
    std::size_t fastest = 0;
    for (std::size_t c = 0; c < order_.size(); ++c)
      if (perStep(c) < perStep(fastest)) fastest = c;
    const std::size_t chosen = perStep(fastest) < 0.95 * perStep(0) ? fastest : 0;
    best_ = order_[chosen];
    measured_ = perStep(chosen);
    trial_ = -1;
    sinceTrial_ = windowTime_ = 0;
    windowSteps_ = 0;
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
  ThreadTuner() = default;
  static constexpr int kMinSliceSteps = 2;
  static constexpr double kLoser = 2;          // this much slower than the best: timed once only
  static constexpr double kWindowSeconds = 1;  // stepping time over which a slowdown is judged

  double perStep(std::size_t c) const { return steps_[c] ? time_[c] / static_cast<double>(steps_[c]) : 1e300; }

  // Running with the best count: time for a new trial?
  void running(double seconds) {
    sinceTrial_ += seconds;
    windowTime_ += seconds;
    ++windowSteps_;
    if (windowTime_ >= kWindowSeconds) {
      const bool slower = windowTime_ / static_cast<double>(windowSteps_) > settings_.slowdown * measured_;
      windowTime_ = 0;
      windowSteps_ = 0;
      if (slower) {
        startTrial();
        return;
      }
    }
    if (sinceTrial_ >= settings_.retrialSeconds) startTrial();
  }

  // Time the present best first, then the other candidates, `rounds` times.
  void startTrial() {
    order_ = {best_};
    for (int t : candidates_)
      if (t != best_) order_.push_back(t);
    trial_ = 0;
    out_.assign(order_.size(), false);
    time_.assign(order_.size(), 0);
    steps_.assign(order_.size(), 0);
    startSlice(best_);
  }

  void startSlice(int t) {
    sliceTime_ = 0;
    sliceSteps_ = 0;
    if (t != current_ || history_.empty()) skip_ = true;
    use(t);
  }

  void use(int t) {
    current_ = t;
    omp_set_num_threads(t);
    if (std::find(history_.begin(), history_.end(), t) == history_.end()) history_.push_back(t);
  }

  Settings settings_;
  std::vector<int> candidates_;  // counts to time, largest first
  std::vector<int> order_;       // the order of the present trial (best first)
  std::vector<double> time_;     // stepping time of each in order_ in this trial
  std::vector<long> steps_;      // and its steps
  std::vector<bool> out_;        // timed once and far slower: not timed again in this trial
  int best_ = 1, current_ = 1;
  int trial_ = -1;               // slice being timed (candidate trial_ % size); -1: running with best_
  bool skip_ = false;
  double sliceTime_ = 0;
  long sliceSteps_ = 0;
  double measured_ = 0;          // mean step time of best_ in the last trial
  double sinceTrial_ = 0, windowTime_ = 0;
  long windowSteps_ = 0;
  std::vector<int> history_;
  std::map<int, double> secondsWith_;
};

}  // namespace sph
