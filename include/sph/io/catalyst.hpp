// In-situ views of a run through ParaView Catalyst (`sph run --catalyst
// SCRIPT.py [--catalyst_every N]`): at the start, every N steps and at the
// end the particles, as the vtkPolyData of a snapshot (snapshot_polydata.hpp),
// are handed to a legacy Catalyst pipeline script, besides the usual output.
// The adaptor is the plugin libsph_catalyst.so (src/catalyst_adaptor.cpp),
// loaded with dlopen here only when a script is given, so that plain runs
// never load ParaView or Python. docs/paraview.md shows the shipped scripts
// (paraview/catalyst_png.py, paraview/catalyst_live.py) and the costs.
#pragma once

#include "sph/io/vtp_io.hpp"

#include "sph/mpi/session.hpp"

#include <memory>
#include <string>

namespace sph {

class Catalyst {
 public:
  // Loads the plugin (next to the sph executable, or SPH_CATALYST_PLUGIN)
  // and the script. Throws CaseError, one line naming the key `catalyst`
  // and the file, when the script is missing, not a file, not Python, not a
  // Catalyst script or fails to load, or when the plugin cannot be loaded.
  // On several MPI ranks every rank constructs it with the run's ranks.
  Catalyst(const std::string& script, const std::string& runFolder, const std::string& runName,
           const mpi::Communicator& ranks = {});
  ~Catalyst();
  Catalyst(const Catalyst&) = delete;
  Catalyst& operator=(const Catalyst&) = delete;

  // Offers the particles to the script (last: the run's last step, which
  // the script always gets). Returns "" or the script's error, in one line.
  template <int D>
  std::string offer(const Particles<D>& P, const SnapshotInfo& info, bool last);

  const std::string& script() const { return script_; }

 private:
  struct Plugin;
  void loadPlugin();
  void agree(const std::string& failure) const;
  std::unique_ptr<Plugin> plugin_;
  std::string script_;
  mpi::Communicator ranks_;
};

// Where sph looks for libsph_catalyst.so.
std::string catalystPluginPath();

}  // namespace sph
