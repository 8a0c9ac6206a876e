// The start of a run: check the case, build or read back its particles and
// check the output folder, before anything is written (run_start.hpp).
#include "sph/run_start.hpp"

#include "sph/case_file.hpp"
#include "sph/io/number_format.hpp"
#include "sph/io/pvd_series.hpp"

#include <filesystem>
#include <new>
#include <ostream>
#include <stdexcept>

namespace sph {

template <int D>
std::optional<RunStart<D>> startRun(const CaseConfig& given, std::ostream& err) {
  RunStart<D> s;
  s.resuming = !given.resume.empty();
  ResolvedCase& c = s.c;
  try {
    validateCase(given);
    c = withDefaults(given);
    if (s.resuming) {
      s.previous = readRunRecord(c.output);
      if (s.previous.dimension != D || s.previous.name != c.name)
        throw CaseError("resume: run.json of " + c.output + " does not match its run.case");
      const PvdSeries series = PvdSeries::load((std::filesystem::path(c.output) / (c.name + ".pvd")).string());
      if (series.entries().empty()) throw CaseError("resume: the series of " + c.output + " has no snapshot");
      s.resumeSnapshot = (std::filesystem::path(c.output) / series.entries().back().file).string();
      s.init = resumeState<D>(s.resumeSnapshot);
    } else {
      s.init = buildInitialState<D>(c);
    }
    const Real t0 = s.init.startTime;
    if (!(c.endTime > t0 * (1 + 1e-12)))
      throw CaseError("end_time = " + shortestDecimal(c.endTime) + " s is not after the start, t = " +
                      shortestDecimal(t0) + " s " +
                      (s.resuming ? "(the run reached it: give --end_time T, later, to run further)"
                                  : "(of particle_file; end_time is absolute)"));
    if ((c.endTime - t0) / c.dt > kMaxSteps)
      throw CaseError("(end_time - start) / dt is more than " + shortestDecimal(kMaxSteps) + " steps");
    checkOutputFolder(c.output, c.overwrite, s.resuming);
  } catch (const CaseError& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";  // values are echoed: no raw control bytes
    return std::nullopt;
  } catch (const std::bad_alloc&) {
    err << "sph: error: not enough memory for the particles of this case (reduce spacing, "
           "star_particles or the block/disc size)\n";
    return std::nullopt;
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";
    return std::nullopt;
  }
  for (const std::string& note : unusedKeyNotes(c)) err << "sph: warning: " << escapeControl(note) << "\n";
  return s;
}

template std::optional<RunStart<2>> startRun<2>(const CaseConfig&, std::ostream&);
template std::optional<RunStart<3>> startRun<3>(const CaseConfig&, std::ostream&);

}  // namespace sph
