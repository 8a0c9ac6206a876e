// Loads the Catalyst plugin with dlopen and hands it the particles
// (sph/io/catalyst.hpp; the plugin's C interface is sph/io/catalyst_plugin.h).
#include "sph/io/catalyst.hpp"

#include "sph/case_config.hpp"
#include "sph/io/catalyst_plugin.h"
#include "sph/io/snapshot_polydata.hpp"
#include "sph/mpi/collectives.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

namespace sph {

struct Catalyst::Plugin {
  void* handle = nullptr;
  int (*abi)() = nullptr;
  int (*initialize)(const char*, const char*, const char*, void*, char*, size_t) = nullptr;
  int (*request)(double, long, int, char*, size_t) = nullptr;
  int (*coprocess)(void*, char*, size_t) = nullptr;
  void (*finalize)() = nullptr;
  bool running = false;
  char error[1024] = {};
  MPI_Comm comm = MPI_COMM_NULL;  // several ranks: Catalyst's duplicate of the run's
};

std::string catalystPluginPath() {
  if (const char* env = std::getenv("SPH_CATALYST_PLUGIN"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ((ec ? std::filesystem::path(".") : exe.parent_path()) / "libsph_catalyst.so").string();
}

namespace {
template <class F>
void symbol(void* handle, const char* name, F& f, const std::string& path) {
  f = reinterpret_cast<F>(dlsym(handle, name));
  if (!f) throw CaseError("catalyst: the plugin " + path + " cannot be used: it has no " + name);
}
}  // namespace

// The checks and loading each process makes alone (throws CaseError).
void Catalyst::loadPlugin() {
  std::error_code ec;
  if (!std::filesystem::exists(script_, ec))
    throw CaseError("catalyst: script " + script_ + " does not exist");
  if (!std::filesystem::is_regular_file(script_, ec))
    throw CaseError("catalyst: " + script_ + " is not a file (a Catalyst pipeline script, .py)");
  if (access(script_.c_str(), R_OK) != 0) throw CaseError("catalyst: script " + script_ + " cannot be read");
  const std::string path = catalystPluginPath();
  // RTLD_GLOBAL: Python's extension modules, imported later by the
  // script, take the interpreter's symbols from the global scope.
  plugin_->handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (!plugin_->handle) {
    const char* why = dlerror();
    throw CaseError("catalyst: the plugin " + path + " cannot be loaded (" + (why ? why : "?") +
                    "): build it with `cmake --build build --target sph_catalyst`");
  }
  symbol(plugin_->handle, "sph_catalyst_abi", plugin_->abi, path);
  if (plugin_->abi() != SPH_CATALYST_ABI)
    throw CaseError("catalyst: the plugin " + path + " is of another sph version: rebuild it");
  symbol(plugin_->handle, "sph_catalyst_initialize", plugin_->initialize, path);
  symbol(plugin_->handle, "sph_catalyst_request", plugin_->request, path);
  symbol(plugin_->handle, "sph_catalyst_coprocess", plugin_->coprocess, path);
  symbol(plugin_->handle, "sph_catalyst_finalize", plugin_->finalize, path);
}

// On several ranks: every rank throws when any rank failed (this one's
// message, or the first failing rank's, named: only rank 0 prints), so that
// none goes on alone into the collective calls that follow (MPI_Comm_dup,
// ParaView's start). A rank that started Catalyst and throws here leaves it
// unfinished: its finish would wait for the ranks that have none.
void Catalyst::agree(const std::string& failure) const {
  if (mpi::allMax(ranks_, failure.empty() ? 0 : 1) == 0) return;
  // (Every rank takes part in the gathers before any throws.)
  const std::vector<char> mine(failure.begin(), failure.end());
  const std::vector<int> lengths = mpi::allGather(ranks_, std::vector<int>{static_cast<int>(mine.size())});
  const std::vector<char> all = mpi::allGather(ranks_, mine);
  if (!failure.empty()) throw CaseError(failure);
  std::size_t at = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    if (lengths[r] > 0)
      throw CaseError(std::string(all.begin() + static_cast<long>(at), all.begin() + static_cast<long>(at + lengths[r])) +
                      " (on MPI rank " + std::to_string(r) + ")");
    at += static_cast<std::size_t>(lengths[r]);
  }
  throw CaseError("catalyst: script " + script_ + " failed to load on another MPI rank");
}

Catalyst::Catalyst(const std::string& script, const std::string& runFolder, const std::string& runName,
                   const mpi::Communicator& ranks)
    : plugin_(std::make_unique<Plugin>()), script_(script), ranks_(ranks) {
  std::string failure;
  try {
    loadPlugin();
  } catch (const CaseError& e) {
    failure = e.what();
  }
  agree(failure);
  std::error_code ec;
  const std::string absolute = std::filesystem::absolute(script, ec).lexically_normal().string();
  const std::string folder = std::filesystem::absolute(runFolder, ec).lexically_normal().string();
  // Catalyst's own duplicate of the run's communicator: a collective call
  // of ParaView's can never be matched with one of sph's.
  if (ranks_.size > 1) MPI_Comm_dup(ranks_.comm, &plugin_->comm);
  if (plugin_->initialize(absolute.c_str(), folder.c_str(), runName.c_str(),
                          ranks_.size > 1 ? &plugin_->comm : nullptr, plugin_->error, sizeof plugin_->error) != 0)
    failure = "catalyst: script " + script + " " + plugin_->error;
  agree(failure);
  plugin_->running = true;
}

Catalyst::~Catalyst() {
  // The plugin stays loaded: ParaView and Python do not unload cleanly.
  if (plugin_ && plugin_->running) plugin_->finalize();
  if (plugin_ && plugin_->comm != MPI_COMM_NULL) MPI_Comm_free(&plugin_->comm);
}

// On several ranks every rank hands its particles when any rank's script
// wants them, and a failure on any rank is every rank's (a reduction after
// the request and one after the hand-over), so that the ranks stay in
// step. (A script that raises on one rank in the middle of one of
// ParaView's collective calls still leaves the others waiting in it.)
template <int D>
std::string Catalyst::offer(const Particles<D>& P, const SnapshotInfo& info, bool last) {
  const int answer = plugin_->request(info.time, info.step, last ? 1 : 0, plugin_->error, sizeof plugin_->error);
  const int wanted = mpi::allMax(ranks_, answer < 0 ? 2 : answer);  // 2: failed, 1: wanted, 0: not
  if (wanted == 2) return answer < 0 ? plugin_->error : "failed on another MPI rank";
  if (wanted == 0) return "";
  const vtkSmartPointer<vtkPolyData> poly = snapshotPolyData<D>(P, info);
  const int failed = plugin_->coprocess(poly.GetPointer(), plugin_->error, sizeof plugin_->error) != 0;
  if (mpi::allMax(ranks_, failed)) return failed ? plugin_->error : "failed on another MPI rank";
  return "";
}

template std::string Catalyst::offer<2>(const Particles<2>&, const SnapshotInfo&, bool);
template std::string Catalyst::offer<3>(const Particles<3>&, const SnapshotInfo&, bool);

}  // namespace sph
