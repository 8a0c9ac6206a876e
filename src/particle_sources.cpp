#include "sph/particle_sources.hpp"

#include "sph/io/vtp_io.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace sph {
namespace {

std::string fmt(Real x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void requirePositive(const char* key, Real value) {
  if (!(value > 0) || !std::isfinite(value))
    throw CaseError(std::string(key) + " = " + fmt(value) + " is out of range: it must be > 0");
}

void requireSize(const char* key, const std::vector<Real>& v, int dim, bool allowEmpty) {
  if (allowEmpty && v.empty()) return;
  if (static_cast<int>(v.size()) != dim)
    throw CaseError(std::string(key) + " has " + std::to_string(v.size()) +
                    " values: it needs " + std::to_string(dim) + " (one per dimension)");
  for (Real x : v)
    if (!std::isfinite(x)) throw CaseError(std::string(key) + " must hold finite numbers");
}

template <int D>
void addParticle(Particles<D>& P, const Vec<D>& x, const Vec<D>& v, Real m = 0) {
  P.x.push_back(x);
  P.v.push_back(v);
  P.m.push_back(m);
  P.id.push_back(static_cast<std::int64_t>(P.id.size()));
}

// Lattice points min + (i + 1/2) dx, round((max - min)/dx) per axis.
template <int D>
void addBlock(Particles<D>& P, const Vec<D>& lo, const Vec<D>& hi, Real dx, const Vec<D>& v) {
  Eigen::Matrix<long, D, 1> count;
  for (int d = 0; d < D; ++d) count[d] = std::lround((hi[d] - lo[d]) / dx);
  long total = 1;
  for (int d = 0; d < D; ++d) total *= count[d];
  for (long k = 0; k < total; ++k) {
    long rest = k;
    Vec<D> x;
    for (int d = 0; d < D; ++d) {
      x[d] = lo[d] + (static_cast<Real>(rest % count[d]) + 0.5) * dx;
      rest /= count[d];
    }
    addParticle(P, x, v);
  }
}

// Lattice points c + i dx with |x - c| <= R.
template <int D>
void addDisc(Particles<D>& P, const Vec<D>& c, Real R, Real dx, const Vec<D>& v) {
  const long n = static_cast<long>(std::floor(R / dx));
  const long side = 2 * n + 1;
  long total = 1;
  for (int d = 0; d < D; ++d) total *= side;
  for (long k = 0; k < total; ++k) {
    long rest = k;
    Vec<D> x;
    for (int d = 0; d < D; ++d) {
      x[d] = c[d] + static_cast<Real>(rest % side - n) * dx;
      rest /= side;
    }
    if ((x - c).norm() <= R * (1 + 1e-12)) addParticle(P, x, v);
  }
}

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return cells;
}

template <int D>
void addCsv(Particles<D>& P, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CaseError("particle_file " + path + " cannot be opened");
  std::string line;
  std::vector<std::string> header;
  while (std::getline(in, line) && (line.empty() || line[0] == '#')) {}
  header = splitCsvLine(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t k = 0; k < header.size(); ++k) column[header[k]] = k;
  const char* xNames[3] = {"x", "y", "z"};
  const char* vNames[3] = {"vx", "vy", "vz"};
  std::size_t xCol[3], vCol[3];
  bool hasV = column.count("vx") > 0;
  for (int d = 0; d < D; ++d) {
    if (!column.count(xNames[d]))
      throw CaseError("particle_file " + path + ": the header line needs columns x, y" +
                      (D == 3 ? ", z" : "") + " (optionally vx, vy" + (D == 3 ? ", vz" : "") +
                      "); it has: " + line);
    xCol[d] = column[xNames[d]];
    if (hasV) {
      if (!column.count(vNames[d]))
        throw CaseError("particle_file " + path + ": column " + vNames[d] + " is missing");
      vCol[d] = column[vNames[d]];
    }
  }
  long lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto cells = splitCsvLine(line);
    auto number = [&](std::size_t col) {
      try {
        std::size_t used = 0;
        const Real value = std::stod(cells.at(col), &used);
        if (used != cells[col].size() || !std::isfinite(value)) throw std::invalid_argument("");
        return value;
      } catch (const std::exception&) {
        throw CaseError("particle_file " + path + " line " + std::to_string(lineNo) +
                        ": column " + std::to_string(col + 1) + " is not a finite number");
      }
    };
    Vec<D> x, v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) x[d] = number(xCol[d]);
    if (hasV)
      for (int d = 0; d < D; ++d) v[d] = number(vCol[d]);
    addParticle(P, x, v);
  }
}

template <int D>
void addVtp(InitialState<D>& s, const std::string& path) {
  VtpParticles f;
  try {
    f = readVtp(path);
  } catch (const std::runtime_error& e) {
    throw CaseError(std::string("particle_file: ") + e.what());
  }
  const bool withMass = !f.m.empty();
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    Vec<D> x, v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      x[d] = f.x[i][static_cast<std::size_t>(d)];
      if (f.hasVelocity) v[d] = f.v[i][static_cast<std::size_t>(d)];
    }
    addParticle(s.particles, x, v, withMass ? f.m[i] : 0);
    if (!f.id.empty()) s.particles.id.back() = f.id[i];
  }
  s.massesGiven = withMass;
  s.startTime = f.time;
}

template <int D>
void addGenerated(Particles<D>& P, const CaseConfig& c, const Vec<D>& v0) {
  if (!c.blockMin.empty()) addBlock(P, toVec<D>(c.blockMin), toVec<D>(c.blockMax), c.spacing, v0);
  if (!c.discCenter.empty()) addDisc(P, toVec<D>(c.discCenter), c.discRadius, c.spacing, v0);
  for (std::size_t k = 0; k + D <= c.points.size(); k += D) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = c.points[k + static_cast<std::size_t>(d)];
    addParticle(P, x, v0);
  }
}

template <int D>
void addFile(InitialState<D>& s, const CaseConfig& c) {
  const std::filesystem::path path(c.particleFile);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw CaseError("particle_file " + c.particleFile + " does not exist or is not a file");
  const std::string ext = path.extension().string();
  if (ext == ".csv") addCsv(s.particles, c.particleFile);
  else if (ext == ".vtp") addVtp(s, c.particleFile);
  else throw CaseError("particle_file " + c.particleFile + " must end in .csv or .vtp");
}

}  // namespace

long stepsFor(const CaseConfig& c) {
  return static_cast<long>(std::ceil(c.endTime / c.dt - 1e-9));
}

void validateCase(const CaseConfig& c) {
  if (c.model != "seed_wcsph")
    throw CaseError("model = \"" + c.model + "\" is not known: allowed is \"seed_wcsph\"");
  if (c.dimension != 2 && c.dimension != 3)
    throw CaseError("dimension = " + std::to_string(c.dimension) + " is out of range: it must be 2 or 3");
  if (c.name.empty() || c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
    throw CaseError("name = \"" + c.name + "\" is not allowed: use letters, digits, '_', '-' and '.'");
  requirePositive("h", c.h);
  requirePositive("k", c.k);
  requirePositive("rho0", c.rho0);
  if (!(c.mu >= 0) || !std::isfinite(c.mu))
    throw CaseError("mu = " + fmt(c.mu) + " is out of range: it must be >= 0");
  if (!std::isfinite(c.g)) throw CaseError("g must be a finite number");
  if (!(c.restitution >= 0 && c.restitution <= 1))
    throw CaseError("restitution = " + fmt(c.restitution) + " is out of range: it must be in [0, 1]");
  requirePositive("dt", c.dt);
  requirePositive("end_time", c.endTime);
  if (c.outputEvery < 1)
    throw CaseError("output_every = " + std::to_string(c.outputEvery) + " is out of range: it must be >= 1");
  if (c.threads < 0)
    throw CaseError("threads = " + std::to_string(c.threads) + " is out of range: it must be >= 0 (0: all cores)");
  const int D = c.dimension;
  requireSize("domain_min", c.domainMin, D, false);
  requireSize("domain_max", c.domainMax, D, false);
  for (int d = 0; d < D; ++d)
    if (!(c.domainMax[static_cast<std::size_t>(d)] > c.domainMin[static_cast<std::size_t>(d)] + 2 * c.h))
      throw CaseError("domain_max must exceed domain_min by more than 2 h in every dimension "
                      "(walls keep particles h away from each wall)");
  requireSize("block_min", c.blockMin, D, true);
  requireSize("block_max", c.blockMax, D, true);
  requireSize("disc_center", c.discCenter, D, true);
  requireSize("velocity", c.velocity, D, true);
  if (c.blockMin.empty() != c.blockMax.empty())
    throw CaseError("block_min and block_max go together: give both or neither");
  if (!c.blockMin.empty())
    for (int d = 0; d < D; ++d)
      if (!(c.blockMax[static_cast<std::size_t>(d)] > c.blockMin[static_cast<std::size_t>(d)]))
        throw CaseError("block_max must exceed block_min in every dimension");
  if (c.discCenter.empty() != (c.discRadius == 0))
    throw CaseError("disc_center and disc_radius go together: give both or neither");
  if (!c.discCenter.empty()) requirePositive("disc_radius", c.discRadius);
  if ((!c.blockMin.empty() || !c.discCenter.empty())) requirePositive("spacing", c.spacing);
  if (c.points.size() % static_cast<std::size_t>(D) != 0)
    throw CaseError("points has " + std::to_string(c.points.size()) +
                    " values: it needs a multiple of " + std::to_string(D) + " (x y" +
                    (D == 3 ? " z" : "") + " per point)");
  if (c.spacing < 0) throw CaseError("spacing = " + fmt(c.spacing) + " is out of range: it must be > 0");
}

template <int D>
InitialState<D> buildInitialState(const CaseConfig& c) {
  InitialState<D> s;
  Particles<D>& P = s.particles;
  const Vec<D> v0 = c.velocity.empty() ? Vec<D>::Zero() : toVec<D>(c.velocity);
  if (c.particleFile.empty()) addGenerated(P, c, v0);
  else addFile(s, c);
  if (P.x.empty())
    throw CaseError("the case has zero particles: give block_min/block_max, disc_center/disc_radius, "
                    "points or particle_file");
  const Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);
  for (std::size_t i = 0; i < P.x.size(); ++i)
    if (!((P.x[i].array() >= lo.array()).all() && (P.x[i].array() <= hi.array()).all())) {
      std::ostringstream where;
      where << "particle " << i << " at (" << P.x[i].transpose().format(Eigen::IOFormat(Eigen::StreamPrecision, 0, ", ")) << ") lies outside the domain [domain_min, domain_max]";
      throw CaseError(where.str());
    }
  P.resize(P.x.size());
  return s;
}

template InitialState<2> buildInitialState<2>(const CaseConfig&);
template InitialState<3> buildInitialState<3>(const CaseConfig&);

}  // namespace sph
