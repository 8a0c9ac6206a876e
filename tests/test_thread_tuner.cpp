// ThreadTuner's decisions, driven by synthetic step times (no clock): it
// keeps the count with the lower mean step time (not the lower median: an
// oversubscribed team has rare, very slow steps), keeps the present count
// against a gain under 5%, retries when the steps slow down, starts from the
// free cores, and never tunes a tiny scene or a count the user gave.
#include "test_support.hpp"

#include "sph/thread_tuner.hpp"

#include <functional>

using namespace sph;
namespace tt = boost::test_tools;

namespace {

// Restores the test process's OpenMP thread count (the tuner sets it).
struct KeepThreads {
  int saved = omp_get_max_threads();
  ~KeepThreads() { omp_set_num_threads(saved); }
};

// Runs `steps` steps whose time is stepTime(threads, step); returns the
// count in use at the end.
int simulate(ThreadTuner& tuner, long steps, const std::function<double(int, long)>& stepTime) {
  for (long s = 0; s < steps; ++s) tuner.record(stepTime(tuner.threads(), s));
  return tuner.threads();
}

constexpr std::size_t kLarge = 100000;  // particles: well above the serial size

}  // namespace

BOOST_AUTO_TEST_SUITE(thread_tuner)

BOOST_AUTO_TEST_CASE(keeps_the_faster_count) {
  KeepThreads keep;
  for (const double load : {0.0, 2.0}) {  // starting from 2 threads, and from 1
    ThreadTuner faster2(kLarge, 2, load);
    BOOST_TEST(simulate(faster2, 1000, [](int t, long) { return t == 2 ? 1e-3 : 1.8e-3; }) == 2);
    ThreadTuner faster1(kLarge, 2, load);
    BOOST_TEST(simulate(faster1, 1000, [](int t, long) { return t == 2 ? 2.5e-3 : 1.8e-3; }) == 1);
  }
}

// Two threads beside a competing program: most steps fast, every fourth one
// descheduled and 20 times slower. The median favours 2 threads, the
// throughput 1.
BOOST_AUTO_TEST_CASE(judges_by_mean_step_time) {
  KeepThreads keep;
  ThreadTuner tuner(kLarge, 2, 0.0);
  const int chosen = simulate(tuner, 2000, [](int t, long s) { return t == 1 ? 2e-3 : (s % 4 == 0 ? 20e-3 : 1e-3); });
  BOOST_TEST(chosen == 1);
}

// A count far slower than the present one is timed in one slice only.
BOOST_AUTO_TEST_CASE(times_a_far_slower_count_once) {
  KeepThreads keep;
  ThreadTuner tuner(kLarge, 2, 2.0);  // starts with 1
  BOOST_TEST(simulate(tuner, 1000, [](int t, long) { return t == 2 ? 20e-3 : 2e-3; }) == 1);
  BOOST_TEST(tuner.secondsWith().at(2) == 0.1, tt::tolerance(0.25));  // one slice of 0.1 s (+ its warm-up step)
}

BOOST_AUTO_TEST_CASE(keeps_the_present_count_against_a_small_gain) {
  KeepThreads keep;
  ThreadTuner tuner(kLarge, 2, 0.0);  // starts with 2
  BOOST_TEST(tuner.threads() == 2);
  BOOST_TEST(simulate(tuner, 1000, [](int t, long) { return t == 2 ? 1e-3 : 0.97e-3; }) == 2);
  BOOST_TEST((tuner.history() == std::vector<int>{2, 1}));
  // Two rounds of 0.1 s slices with 1 thread (and their warm-up steps).
  BOOST_TEST(tuner.secondsWith().at(1) > 0.2);
  BOOST_TEST(tuner.secondsWith().at(1) < 0.21);
  const double steps1 = std::round(tuner.secondsWith().at(1) / 0.97e-3);
  BOOST_TEST(tuner.secondsWith().at(2) == (1000 - steps1) * 1e-3, tt::tolerance(1e-9));
}

// A competing program starts after 3 s: 2 threads become 4 times slower; the
// tuner notices within a few seconds and moves to 1 thread, long before
// the periodic retrial (20 s).
BOOST_AUTO_TEST_CASE(retries_when_the_steps_slow_down) {
  KeepThreads keep;
  ThreadTuner tuner(kLarge, 2, 0.0);
  double clock = 0;
  double movedAt = -1;
  for (long s = 0; s < 20000 && clock < 10; ++s) {
    const bool competing = clock > 3;
    const double dt = tuner.threads() == 2 ? (competing ? 4e-3 : 1e-3) : 1.8e-3;
    tuner.record(dt);
    clock += dt;
    if (competing && movedAt < 0 && tuner.threads() == 1 && tuner.history().back() == 1) movedAt = clock;
  }
  BOOST_TEST(tuner.threads() == 1);
  BOOST_TEST(movedAt > 3);
  BOOST_TEST(movedAt < 6);
}

BOOST_AUTO_TEST_CASE(starts_from_the_free_cores) {
  KeepThreads keep;
  BOOST_TEST(ThreadTuner(kLarge, 4, 0.0).threads() == 4);
  BOOST_TEST(ThreadTuner(kLarge, 4, 2.2).threads() == 2);
  BOOST_TEST(ThreadTuner(kLarge, 4, 9.0).threads() == 1);
  BOOST_TEST(ThreadTuner(kLarge, 2, 1.6).threads() == 1);
}

BOOST_AUTO_TEST_CASE(tiny_scenes_and_given_counts_are_not_tuned) {
  KeepThreads keep;
  ThreadTuner tiny(10, 2, 0.0);
  BOOST_TEST(!tiny.tuning());
  BOOST_TEST(simulate(tiny, 100, [](int, long) { return 1e-3; }) == 1);
  ThreadTuner given = ThreadTuner::fixed(3);
  BOOST_TEST(simulate(given, 100, [](int t, long) { return t == 3 ? 1.0 : 1e-6; }) == 3);
  BOOST_TEST((given.history() == std::vector<int>{3}));
}

BOOST_AUTO_TEST_SUITE_END()
