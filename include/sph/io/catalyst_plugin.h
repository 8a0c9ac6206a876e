/* The C interface of libsph_catalyst.so (src/catalyst_adaptor.cpp), the
 * ParaView Catalyst adaptor that `sph run --catalyst SCRIPT.py` loads with
 * dlopen (src/catalyst.cpp), so that runs without Catalyst never load
 * ParaView or Python. One Catalyst per process. Every function that can
 * fail returns < 0 and writes one line saying why into error[0 .. size). */
#ifndef SPH_IO_CATALYST_PLUGIN_H
#define SPH_IO_CATALYST_PLUGIN_H

#include <stddef.h>

#define SPH_CATALYST_ABI 2

#ifdef __cplusplus
extern "C" {
#endif

/* SPH_CATALYST_ABI of the plugin: sph refuses another one. */
int sph_catalyst_abi(void);

/* Starts Catalyst (ParaView's server manager and Python) and loads the
 * legacy ("Catalyst 1") pipeline script: it must parse and define
 * RequestDataDescription(datadescription) and DoCoProcessing(datadescription).
 * The script finds run_folder and run_name as string arrays of
 * datadescription.GetUserData(). mpi_comm: NULL on one process, else the
 * address of the MPI_Comm of the run's ranks (every rank calls every
 * function below in the same order; each hands its own particles, and
 * ParaView sees them as one data set of one piece per rank). 0 on success. */
int sph_catalyst_initialize(const char* script, const char* run_folder, const char* run_name, void* mpi_comm,
                            char* error, size_t size);

/* Asks the script whether it wants the particles at this time and step
 * (last: the run's last step, Catalyst's ForceOutput): 1 yes, 0 no. */
int sph_catalyst_request(double time, long step, int last, char* error, size_t size);

/* Hands the particles (a vtkPolyData*, grid "input") to the script's
 * DoCoProcessing, after a request that returned 1. 0 on success. */
int sph_catalyst_coprocess(void* polydata, char* error, size_t size);

/* Calls the script's Finalize() if it has one, and stops Catalyst. */
void sph_catalyst_finalize(void);

#ifdef __cplusplus
}
#endif

#endif
