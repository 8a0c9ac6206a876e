#include "sph/particle_sources.hpp"

#include "sph/io/vtp_io.hpp"
#include "sph/methods.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/toy_star.hpp"
#include "sph/wall_particles.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

namespace sph {
namespace {

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

std::string trimmedLine(const std::string& line) {
  const auto e = line.find_last_not_of(" \t\r");
  return e == std::string::npos ? "" : line.substr(0, e + 1);
}

// A CSV file: a header line naming the columns (x, y[, z][, vx, vy[, vz]],
// in any order), then one particle per line. Lines that are empty or start
// with '#' are skipped. A column that would be silently dropped (unknown, a
// repeat, z in 2D, vy without vx) is an error, as is a row of the wrong width.
template <int D>
void addCsv(Particles<D>& P, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw CaseError("particle_file " + path + " cannot be opened");
  const std::string where = "particle_file " + path;
  const std::string allowed = std::string("x, y") + (D == 3 ? ", z" : "") + " and optionally vx, vy" +
                              (D == 3 ? ", vz" : "") + " (dimension = " + std::to_string(D) + ")";
  auto skipped = [](const std::string& l) {
    return l.empty() || l[0] == '#' || l.find_first_not_of(" \t\r") == std::string::npos;
  };
  std::string line;
  long lineNo = 0;
  while (std::getline(in, line) && (++lineNo, skipped(line))) {}
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte-order mark (spreadsheets write one)
  std::vector<std::string> header = splitCsvLine(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t k = 0; k < header.size(); ++k) {
    std::string& name = header[k];
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    if (!column.emplace(name, k).second)
      throw CaseError(where + ": column " + name + " appears twice in the header line");
  }
  const char* xNames[3] = {"x", "y", "z"};
  const char* vNames[3] = {"vx", "vy", "vz"};
  for (int d = 0; d < D; ++d)
    if (!column.count(xNames[d]))
      throw CaseError(where + ": the header line needs columns x, y" + (D == 3 ? ", z" : "") +
                      " (optionally vx, vy" + (D == 3 ? ", vz" : "") + "); it has: " + trimmedLine(line));
  for (const auto& [name, k] : column) {
    bool known = false;
    for (int d = 0; d < D; ++d) known = known || name == xNames[d] || name == vNames[d];
    if (!known)
      throw CaseError(where + ": header column " + std::to_string(k + 1) + " is '" + name +
                      "'; the columns may be " + allowed);
  }
  std::size_t xCol[3], vCol[3];
  bool hasV = false;
  for (int d = 0; d < D; ++d) hasV = hasV || column.count(vNames[d]) > 0;
  for (int d = 0; d < D; ++d) {
    xCol[d] = column[xNames[d]];
    if (hasV) {
      if (!column.count(vNames[d]))
        throw CaseError(where + ": column " + vNames[d] + " is missing: give all of vx, vy" +
                        (D == 3 ? ", vz" : "") + " or none");
      vCol[d] = column[vNames[d]];
    }
  }
  const std::size_t before = P.x.size();
  while (std::getline(in, line)) {
    ++lineNo;
    if (skipped(line)) continue;
    const auto cells = splitCsvLine(line);
    if (cells.size() != header.size())
      throw CaseError(where + " line " + std::to_string(lineNo) + ": " + std::to_string(cells.size()) +
                      " values, but the header line has " + std::to_string(header.size()) + " columns");
    auto number = [&](std::size_t col) {
      try {
        std::size_t used = 0;
        const Real value = std::stod(cells.at(col), &used);
        if (used != cells[col].size() || !std::isfinite(value)) throw std::invalid_argument("");
        return value;
      } catch (const std::exception&) {
        throw CaseError(where + " line " + std::to_string(lineNo) + ": column " + std::to_string(col + 1) +
                        " is not a finite number");
      }
    };
    Vec<D> x, v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) x[d] = number(xCol[d]);
    if (hasV)
      for (int d = 0; d < D; ++d) v[d] = number(vCol[d]);
    addParticle(P, x, v);
  }
  if (P.x.size() == before) throw CaseError(where + " has a header line but no particles");
}

// What a .vtp gives besides the fluid's positions, velocities, masses and
// ids: its wall particles (kind = 1, in file order), and the densities and
// the surface-tension colour when it has them (an sph snapshot does).
template <int D>
struct FromFile {
  Particles<D> walls;
  std::vector<Real> fluidRho, wallRho, fluidColour;
};

// A .vtp: any PolyData whose points are the particles (velocity, mass, id,
// density, kind, colour point arrays and the TimeValue are read when present).
template <int D>
void addVtp(InitialState<D>& s, FromFile<D>& file, const std::string& path) {
  VtpParticles f;
  try {
    f = readVtp(path);
  } catch (const std::exception& e) {
    throw CaseError(std::string("particle_file ") + e.what());
  }
  const bool withMass = !f.m.empty();
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (D == 2 && (f.x[i][2] != 0 || (f.hasVelocity && f.v[i][2] != 0)))
      throw CaseError("particle_file " + path + ": particle " + std::to_string(i) +
                      " has a z position or velocity other than 0, but the case has dimension = 2");
    Vec<D> x, v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      x[d] = f.x[i][static_cast<std::size_t>(d)];
      if (f.hasVelocity) v[d] = f.v[i][static_cast<std::size_t>(d)];
    }
    const bool wall = !f.kind.empty() && f.kind[i] == kWall;
    Particles<D>& to = wall ? file.walls : s.particles;
    addParticle(to, x, v, withMass ? f.m[i] : 0);
    if (!f.id.empty()) to.id.back() = f.id[i];
    if (!f.rho.empty()) (wall ? file.wallRho : file.fluidRho).push_back(f.rho[i]);
    if (!f.colour.empty() && !wall) file.fluidColour.push_back(f.colour[i]);
  }
  s.massesGiven = withMass;
  s.startTime = f.time;
}

// Toy stars: star_particles[s] random points in the ball of radius R about
// star_center[s], moving with star_velocity[s]; every particle has mass
// star_mass / (total particles), so a single star has mass M.
template <int D>
void addStars(InitialState<D>& s, const CaseConfig& c) {
  long total = 0;
  for (long n : c.starParticles) total += n;
  const Real m = c.starMass / static_cast<Real>(total);
  for (std::size_t k = 0; k < c.starParticles.size(); ++k) {
    Vec<D> centre, v = Vec<D>::Zero();
    for (int d = 0; d < D; ++d) {
      centre[d] = c.starCenter[k * D + static_cast<std::size_t>(d)];
      if (!c.starVelocity.empty()) v[d] = c.starVelocity[k * D + static_cast<std::size_t>(d)];
    }
    const auto points = randomPointsInBall<D>(centre, c.starRadius,
                                              static_cast<std::size_t>(c.starParticles[k]),
                                              static_cast<unsigned>(c.seed + static_cast<long>(k)));
    for (const auto& x : points) addParticle(s.particles, x, v, m);
  }
  s.massesGiven = true;
}

template <int D>
void addGenerated(InitialState<D>& s, const CaseConfig& c, const Vec<D>& v0) {
  Particles<D>& P = s.particles;
  if (c.starMass != 0) addStars(s, c);
  // Each body with its own velocity (block_velocity, disc_velocity) or v0;
  // `surface` records each generated particle's free-surface height (the
  // top of its body) for the hydrostatic start.
  auto vecAt = [](const std::vector<Real>& v, std::size_t k) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = v[k * D + static_cast<std::size_t>(d)];
    return x;
  };
  for (std::size_t k = 0; k < c.blockMin.size() / D; ++k) {
    addBlock(P, vecAt(c.blockMin, k), vecAt(c.blockMax, k), c.spacing, c.blockVelocity.empty() ? v0 : vecAt(c.blockVelocity, k));
    s.surface.resize(P.x.size(), c.blockMax[k * D + D - 1]);
  }
  for (std::size_t k = 0; k < c.discRadius.size(); ++k) {
    addDisc(P, vecAt(c.discCenter, k), c.discRadius[k], c.spacing, c.discVelocity.empty() ? v0 : vecAt(c.discVelocity, k));
    s.surface.resize(P.x.size(), c.discCenter[k * D + D - 1] + c.discRadius[k]);
  }
  for (std::size_t k = 0; k + D <= c.points.size(); k += D) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = c.points[k + static_cast<std::size_t>(d)];
    addParticle(P, x, v0);
  }
}

template <int D>
void addFile(InitialState<D>& s, FromFile<D>& file, const CaseConfig& c) {
  const std::filesystem::path path(c.particleFile);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw CaseError("particle_file " + c.particleFile + " does not exist or is not a file");
  const std::string ext = path.extension().string();
  if (ext == ".csv") addCsv(s.particles, c.particleFile);
  else if (ext == ".vtp" || ext == ".pvtp") addVtp(s, file, c.particleFile);
  else throw CaseError("particle_file " + c.particleFile + " must end in .csv, .vtp or .pvtp");
}

}  // namespace

// The Taylor-Green vortex array of a periodic square box of side L
// (Taylor & Green 1937; the 2D decaying solution, e.g. Adami, Hu & Adams
// 2013, J. Comput. Phys. 241, sec. 4.1), k = 2 pi / L:
//   u = -U cos(k x) sin(k y),  v = U sin(k x) cos(k y),
//   p = -rho0 U^2 / 4 (cos(2 k x) + cos(2 k y)),
// decaying as exp(-2 nu k^2 t) (velocity). The density is the EOS inverse of
// p and the mass rho dx^D, so every particle keeps its lattice volume.
template <int D>
void addTaylorGreenFlow(Particles<D>& P, const ResolvedCase& c) {
  const EquationOfState eos = methodRow(eosMethods(), "eos", c.eos).make(c);
  const Real U = c.flowSpeed, L = c.domainMax[0] - c.domainMin[0], k = 2 * std::acos(Real(-1)) / L;
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    const Real x = P.x[i][0] - c.domainMin[0], y = P.x[i][1] - c.domainMin[1];
    P.v[i][0] = -U * std::cos(k * x) * std::sin(k * y);
    P.v[i][1] = U * std::sin(k * x) * std::cos(k * y);
    const Real p = -c.rho0 * U * U / 4 * (std::cos(2 * k * x) + std::cos(2 * k * y));
    P.rho[i] = std::visit([&](const auto& e) { return e.density(p + c.backgroundPressure); }, eos);
    P.m[i] *= P.rho[i] / c.rho0;
  }
}

template <int D>
InitialState<D> buildInitialState(const ResolvedCase& c) {
  InitialState<D> s;
  Particles<D>& P = s.particles;
  const Vec<D> v0 = c.velocity.empty() ? Vec<D>::Zero() : toVec<D>(c.velocity);
  FromFile<D> file;
  if (c.particleFile.empty()) addGenerated(s, c, v0);
  else addFile(s, file, c);
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
  // Fluid bodies must not overlap a solid one.
  for (std::size_t k = 0; k + D <= c.obstacleMin.size(); k += D)
    for (std::size_t i = 0; i < P.x.size(); ++i) {
      bool in = true;
      for (int d = 0; d < D; ++d)
        in &= P.x[i][d] > c.obstacleMin[k + static_cast<std::size_t>(d)] &&
              P.x[i][d] < c.obstacleMax[k + static_cast<std::size_t>(d)];
      if (in)
        throw CaseError("the fluid overlaps obstacle " + std::to_string(k / D + 1) +
                        " (obstacle_min/obstacle_max): fluid particle " + std::to_string(i) + " lies inside it");
    }
  const std::size_t nFluid = P.x.size();
  const bool wcsph = composedModel(c);
  // wcsph: masses from the lattice, m = rho0 dx^D (the seed scales them to
  // a mean density of rho0, as the seed says).
  if (wcsph && c.spacing > 0 && !s.massesGiven) {
    for (auto& m : P.m) m = static_cast<Narrow>(c.rho0 * std::pow(c.spacing, D));
    s.massesGiven = true;
  }
  // Wall particles, after the fluid: a particle file's own (a snapshot's
  // walls carry their density, which dynamic walls integrate), else the case's.
  const bool particleWalls = wcsph && wallParticles(c);
  const Real mWall = c.rho0 * std::pow(c.spacing, D);
  if (!file.walls.x.empty()) {
    const std::string where = "particle_file " + c.particleFile + " holds " + std::to_string(file.walls.x.size()) +
                              " wall particles (kind = 1)";
    if (!particleWalls)
      throw CaseError(where + ", but the case has none (they need model = wcsph, walls = true and boundary = "
                      "dummy, dynamic or repulsive)");
    const std::size_t made = wallParticlePositions<D>(c, wallLayersUsed(c)).size();
    if (file.walls.x.size() != made)
      throw CaseError(where + ", but the case makes " + std::to_string(made) +
                      ": its domain, obstacles, spacing or wall layers differ from the run that wrote the file");
    for (std::size_t i = 0; i < file.walls.x.size(); ++i) {
      addParticle<D>(P, file.walls.x[i], file.walls.v[i], file.walls.m[i] > 0 ? file.walls.m[i] : mWall);
      P.id.back() = file.walls.id[i];
    }
  } else if (particleWalls) {
    const int layers = wallLayersUsed(c);
    // A sliding lid: the wall particles above the box carry its velocity
    // u_w, which the wall terms see (dummy_adami2012.hpp); none moves.
    const Real top = c.domainMax[static_cast<std::size_t>(D - 1)];
    const Vec<D> uLid = c.lidVelocity.empty() ? Vec<D>::Zero() : toVec<D>(c.lidVelocity);
    for (const Vec<D>& x : wallParticlePositions<D>(c, layers))
      addParticle<D>(P, x, x[D - 1] > top ? uLid : Vec<D>::Zero(), mWall);
  }
  P.resize(P.x.size(), nFluid);
  // Density: rho0, or the hydrostatic balance p = rho0 g (H - y) with H the
  // top of the particle's own block or disc (explicit points: p = 0). The lattice stays as it is and the masses carry
  // the compression (m = rho dx^D), so that every particle's volume m/rho is
  // still dx^D: the state is in balance as it starts, with nothing to settle
  // (compressing densities alone would leave the pressure gradient short by
  // rho/rho0). Summation density and the seed recompute rho anyway.
  std::fill(P.rho.begin(), P.rho.end(), c.rho0);
  const bool densitiesGiven = !file.fluidRho.empty();  // an sph snapshot: its densities, no hydrostatic start
  std::copy(file.fluidRho.begin(), file.fluidRho.end(), P.rho.begin());
  std::copy(file.wallRho.begin(), file.wallRho.end(), P.rho.begin() + static_cast<std::ptrdiff_t>(nFluid));
  // Colour of the surface-tension phase: 1 inside the colour box or the
  // colour ellipse (everywhere when neither is given), 0 outside and for walls.
  if (wcsph && surfaceTensionCurvature(c) && !file.fluidColour.empty()) {
    P.colour.assign(P.size(), 0);
    std::copy(file.fluidColour.begin(), file.fluidColour.end(), P.colour.begin());
  } else if (wcsph && surfaceTensionCurvature(c)) {
    P.colour.assign(P.size(), 0);
    const bool box = !c.colourBoxMin.empty(), ellipse = !c.colourEllipseCenter.empty();
    for (std::size_t i = 0; i < nFluid; ++i) {
      bool inBox = box, inEllipse = ellipse;
      Real e = 0;
      for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
        const Real x = P.x[i][static_cast<int>(d)];
        if (box) inBox &= x >= c.colourBoxMin[d] && x <= c.colourBoxMax[d];
        if (ellipse) e += std::pow((x - c.colourEllipseCenter[d]) / c.colourEllipseRadii[d], 2);
      }
      if (ellipse) inEllipse = e <= 1;
      P.colour[i] = (!box && !ellipse) || inBox || inEllipse ? 1 : 0;
    }
  }
  if (wcsph && c.hydrostaticStart && !densitiesGiven) {
    const EquationOfState eos = methodRow(eosMethods(), "eos", c.eos).make(c);
    // Wall particles take the highest body's surface.
    const Real top = s.surface.empty() ? 0 : *std::max_element(s.surface.begin(), s.surface.end());
    const bool wallMassFixed = boundaryChoice(c).wallDensityFromFluid;
    for (std::size_t i = 0; i < P.size(); ++i) {
      const Real H = i < s.surface.size() ? s.surface[i] : (i < nFluid ? P.x[i][D - 1] : top);
      const Real p = std::max(Real(0), c.rho0 * -gravityVector<D>(c)[D - 1] * (H - P.x[i][D - 1]));
      P.rho[i] = std::visit([&](const auto& e) { return e.density(p + c.backgroundPressure); }, eos);
      if (i < nFluid || !wallMassFixed) P.m[i] *= P.rho[i] / c.rho0;
    }
  }
  if (wcsph && initialFlow(c) == InitialFlow::kTaylorGreen) addTaylorGreenFlow(P, c);
  return s;
}

template <int D>
InitialState<D> resumeState(const std::string& snapshot) {
  VtpParticles f;
  try {
    f = readVtp(snapshot);
  } catch (const std::exception& e) {
    throw CaseError(std::string("resume: ") + e.what());
  }
  const std::size_t n = f.x.size();
  auto need = [&](bool ok, const char* what) {
    if (!ok) throw CaseError("resume: " + snapshot + " has no " + what + " array (not a snapshot sph wrote?)");
  };
  need(f.hasVelocity, "velocity");
  need(!f.m.empty(), "mass");
  need(!f.id.empty(), "id");
  need(!f.a.empty(), "acceleration");
  need(!f.rho.empty(), "density");
  InitialState<D> s;
  Particles<D>& P = s.particles;
  auto vec = [](const std::array<Real, 3>& a) {
    Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = a[static_cast<std::size_t>(d)];
    return v;
  };
  // A .pvtp's pieces (a run on several ranks) each list their fluid, then
  // their walls: all fluid first, each in its piece's order. One .vtp must
  // already be so.
  const bool pieces = std::filesystem::path(snapshot).extension() == ".pvtp";
  auto isWall = [&](std::size_t i) { return !f.kind.empty() && f.kind[i] == kWall; };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (pieces) std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return !isWall(i); });
  std::size_t fluid = n;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    addParticle(P, vec(f.x[i]), vec(f.v[i]), f.m[i]);
    P.id.back() = f.id[i];
    if (isWall(i) && fluid == n) fluid = k;
    if (!isWall(i) && fluid < n)
      throw CaseError("resume: " + snapshot + " lists a fluid particle after a wall particle (not a snapshot sph wrote?)");
  }
  P.resize(n, fluid);
  for (std::size_t k = 0; k < n; ++k) {
    P.a[k] = vec(f.a[order[k]]);
    P.rho[k] = f.rho[order[k]];
  }
  // The rates the integrator carries into its next step.
  auto scalars = [&](const std::vector<Real>& from, auto& to) {
    if (from.empty()) return;
    to.clear();
    for (std::size_t k = 0; k < from.size(); ++k) to.push_back(from[order[k]]);
  };
  auto vectors = [&](const std::vector<std::array<Real, 3>>& from, std::vector<Vec<D>>& to) {
    if (from.empty()) return;
    to.clear();
    for (std::size_t k = 0; k < from.size(); ++k) to.push_back(vec(from[order[k]]));
  };
  scalars(f.drho, P.drho);
  scalars(f.colour, P.colour);  // surface tension: the phases as they were
  vectors(f.vXsph, P.vXsph);
  vectors(f.vPrev, P.vPrev);  // two-step leap-frog
  scalars(f.rhoPrev, P.rhoPrev);
  vectors(f.xList, P.xList);  // the neighbour list's build (scene.hpp)
  s.inSortOrder = !pieces;
  s.massesGiven = true;
  s.startTime = f.time;
  s.startStep = f.step;
  return s;
}

template InitialState<2> resumeState<2>(const std::string&);
template InitialState<3> resumeState<3>(const std::string&);
template InitialState<2> buildInitialState<2>(const ResolvedCase&);
template InitialState<3> buildInitialState<3>(const ResolvedCase&);

}  // namespace sph
