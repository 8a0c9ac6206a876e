// The probe files of a run (sph/probes.hpp says what each probe measures):
//   probes.csv   time, then per point probe: pressure, density, velocity
//                (and with probe_window the pressure's moving average)
//   heights.csv  time, then the water height at each height gauge
//   front.csv    time, the surge front's x
// Each has a header line naming every column with its unit (2D quantities
// per unit depth). Rows are sampled every probe_interval seconds of
// simulated time (0: every step) and the files are rewritten atomically at
// every snapshot, like energy.csv, so they always match the series.
#pragma once

#include "sph/case_config.hpp"
#include "sph/io/number_format.hpp"
#include "sph/probes.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <utility>
#include <sstream>
#include <string>
#include <vector>

namespace sph {

// Probe names: probe_names split at commas (blanks trimmed), or p1, p2, ...
inline std::vector<std::string> probeNames(const CaseConfig& c, std::size_t count) {
  std::vector<std::string> names;
  std::stringstream in(c.probeNames);
  for (std::string name; std::getline(in, name, ',');) {
    const auto a = name.find_first_not_of(" \t"), b = name.find_last_not_of(" \t");
    names.push_back(a == std::string::npos ? "" : name.substr(a, b - a + 1));
  }
  if (c.probeNames.empty())
    for (std::size_t k = 0; k < count; ++k) names.push_back("p" + std::to_string(k + 1));
  return names;
}

template <int D>
class ProbeFiles {
 public:
  ProbeFiles(const CaseConfig& c, const Kernel<D>& kernel)
      : kernel_(kernel), dx_(c.spacing), interval_(c.probeInterval), heights_(c.heightProbes), front_(c.frontProbe),
        shepard_(c.probeInterpolation != "plain"), radius_(c.probeRadius), window_(c.probeWindow) {
    if (c.domainMin.size() == D && c.domainMax.size() == D) {
      for (int d = 0; d < D; ++d) {
        box_.lo[d] = c.domainMin[static_cast<std::size_t>(d)];
        box_.length[d] = c.domainMax[static_cast<std::size_t>(d)] - c.domainMin[static_cast<std::size_t>(d)];
      }
      box_.axes = periodicAxes(c);
    }
    for (std::size_t k = 0; k + D <= c.probePoints.size(); k += D) {
      Vec<D> x;
      for (int d = 0; d < D; ++d) x[d] = c.probePoints[k + static_cast<std::size_t>(d)];
      points_.push_back(x);
    }
    names_ = probeNames(c, points_.size());
    // Sensors (probe_radius > 0): each a disc on the wall face nearest to
    // its point, among the domain box's faces and the obstacles'.
    std::vector<std::pair<Vec<D>, Vec<D>>> boxes;
    unsigned skip = 0;
    if (c.domainMin.size() == D && c.domainMax.size() == D) {
      Vec<D> lo, hi;
      for (int d = 0; d < D; ++d)
        lo[d] = c.domainMin[static_cast<std::size_t>(d)], hi[d] = c.domainMax[static_cast<std::size_t>(d)];
      boxes.push_back({lo, hi});
      skip = periodicAxes(c);
    }
    for (std::size_t k = 0; k + D <= c.obstacleMin.size() && k + D <= c.obstacleMax.size(); k += D) {
      Vec<D> lo, hi;
      for (int d = 0; d < D; ++d)
        lo[d] = c.obstacleMin[k + static_cast<std::size_t>(d)], hi[d] = c.obstacleMax[k + static_cast<std::size_t>(d)];
      boxes.push_back({lo, hi});
    }
    const Real h = std::visit([](const auto& W) { return W.support() / 2; }, kernel_);
    for (const auto& x : points_) {
      normals_.push_back(boxes.empty() ? D - 1 : nearestFaceAxis<D>(x, boxes, skip));
      discs_.push_back(sensorDiscPoints<D>(x, normals_.back(), radius_, h));
    }
    history_.resize(points_.size());
    const char* pressure = D == 2 ? "N/m" : "Pa";
    const char* density = D == 2 ? "kg/m^2" : "kg/m^3";
    const char* axes = "xyz";
    if (!points_.empty()) {
      pointText_ = "time [s]";
      for (const auto& name : names_) {
        pointText_ += "," + name + " pressure [" + pressure + "]," + name + " density [" + density + "]";
        for (int d = 0; d < D; ++d) pointText_ += "," + name + " v" + axes[d] + " [m/s]";
        if (window_ > 0) pointText_ += "," + name + " pressure filtered [" + pressure + "]";
      }
      pointText_ += "\n";
    }
    if (!heights_.empty()) {
      heightText_ = "time [s]";
      for (std::size_t k = 0; k + (D - 1) <= heights_.size(); k += D - 1) {
        heightText_ += ",height at ";
        for (int d = 0; d + 1 < D; ++d) heightText_ += (d ? " " : "") + std::string(1, axes[d]) + "=" + number(heights_[k + static_cast<std::size_t>(d)]);
        heightText_ += " [m]";
      }
      heightText_ += "\n";
    }
    if (front_) frontText_ = "time [s],front x [m]\n";
  }

  bool any() const { return !points_.empty() || !heights_.empty() || front_; }

  // Sample at time t when a sample is due (every step for interval 0).
  void sample(const Particles<D>& P, Real t, const std::string& timeText) {
    if (!any()) return;
    if (interval_ > 0 && t < next_ * (1 - 1e-12) - 1e-12 * interval_) return;
    if (interval_ > 0) next_ = (std::floor(t / interval_ * (1 + 1e-12) + 1e-9) + 1) * interval_;
    if (!points_.empty()) {
      pointText_ += timeText;
      for (std::size_t k = 0; k < points_.size(); ++k) {
        const ProbeValues<D> v =
            sensorAt(P, kernel_, points_[k], discs_[k], radius_, kDryWeight, box_, shepard_, comm_);
        pointText_ += "," + value(v.wet, v.pressure) + "," + value(v.wet, v.density);
        for (int d = 0; d < D; ++d) pointText_ += "," + value(v.wet, v.velocity[d]);
        if (window_ > 0) pointText_ += "," + number(filtered(k, t, v.wet ? v.pressure : 0));
      }
      pointText_ += "\n";
    }
    if (!heights_.empty()) {
      heightText_ += timeText;
      for (std::size_t k = 0; k + (D - 1) <= heights_.size(); k += D - 1)
        heightText_ += "," + number(waterHeightAt(P, &heights_[k], dx_, comm_));
      heightText_ += "\n";
    }
    if (front_) frontText_ += timeText + "," + number(frontPosition(P, dx_, comm_)) + "\n";
  }

  // The files' rows not yet written (the writer empties them), and their
  // names; only the files the case has.
  struct File {
    const char* name;
    std::string* text;
  };
  std::vector<File> files() {
    std::vector<File> f;
    if (!points_.empty()) f.push_back({"probes.csv", &pointText_});
    if (!heights_.empty()) f.push_back({"heights.csv", &heightText_});
    if (front_) f.push_back({"front.csv", &frontText_});
    return f;
  }

  // A resumed run keeps the rows up to its snapshot: `keep(name)` returns
  // them (header included), "" when the file is not there.
  template <class Keep>
  void resume(Real t, Keep&& keep) {
    for (auto [name, text] : {std::pair{"probes.csv", &pointText_}, std::pair{"heights.csv", &heightText_},
                              std::pair{"front.csv", &frontText_}}) {
      if (text->empty()) continue;
      const std::string kept = keep(name);
      if (!kept.empty()) *text = kept;
    }
    if (interval_ > 0) next_ = (std::floor(t / interval_ * (1 + 1e-12) + 1e-9) + 1) * interval_;
    // The moving average's samples within the window, from the kept rows.
    if (window_ > 0 && !points_.empty()) {
      std::stringstream rows(pointText_);
      std::string line;
      std::getline(rows, line);  // header
      const std::size_t group = 2 + D + 1;
      while (std::getline(rows, line)) {
        std::vector<Real> cells;
        std::stringstream in(line);
        for (std::string cell; std::getline(in, cell, ',');) cells.push_back(std::strtod(cell.c_str(), nullptr));
        if (cells.size() != 1 + group * points_.size()) continue;
        for (std::size_t k = 0; k < points_.size(); ++k) {
          const Real p = cells[1 + k * group];
          remember(k, cells[0], std::isfinite(p) ? p : 0);
        }
      }
    }
  }

  // The sensors' normal axes (probe_radius: the disc lies across it).
  const std::vector<int>& sensorNormals() const { return normals_; }

 private:
  // probe_window: the mean of probe k's samples in (t - window, t].
  void remember(std::size_t k, Real t, Real p) {
    auto& h = history_[k];
    h.emplace_back(t, p);
    while (!h.empty() && h.front().first <= t - window_ * (1 - 1e-9)) h.pop_front();
  }
  Real filtered(std::size_t k, Real t, Real p) {
    remember(k, t, p);
    Real sum = 0;
    for (const auto& s : history_[k]) sum += s.second;
    return sum / static_cast<Real>(history_[k].size());
  }

  static constexpr Real kDryWeight = 0.1;  // of a full support's sum_j V_j W = 1
  static std::string number(Real x) { return significant(x, 10); }
  static std::string value(bool wet, Real x) { return wet ? number(x) : "nan"; }

  Kernel<D> kernel_;
  PeriodicBox<D> box_;  // minimum image for the point probes along periodic axes
  Real dx_, interval_;
  std::vector<Vec<D>> points_;
  std::vector<std::string> names_;
  std::vector<Real> heights_;
  bool front_;
  bool shepard_;  // probe_interpolation: shepard (default) or plain
  Real radius_, window_;  // probe_radius, probe_window
  std::vector<int> normals_;
  std::vector<std::vector<Vec<D>>> discs_;
  std::vector<std::deque<std::pair<Real, Real>>> history_;
  Real next_ = 0;
  std::string pointText_, heightText_, frontText_;
  // The ranks of the run: each samples its own fluid and the sums and
  // maxima are reduced (rank 0 writes the files).
  mpi::Communicator comm_ = mpi::world();
};

}  // namespace sph
