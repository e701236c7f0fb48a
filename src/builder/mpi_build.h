#pragma once
// `mpirun -np N interiornet dataset build DIR` (issue 16): the build on N ranks with Open MPI.
// Rank 0 coordinates: it alone opens the job state (build_state.h), hands out one unit at a
// time to whichever worker asks (dynamic distribution: long and short units mix, a slow rank
// simply takes fewer) and records what each reports. Ranks 1..N-1 run units. With one rank
// the build runs as buildLocal. Output bytes do not depend on N (units are independent and
// the sequence pipeline writes the same bytes in any order).
//
// Stopping: a SIGTERM or SIGINT (mpirun forwards them to every rank; Slurm sends one before it
// kills a job) makes each worker stop at its unit's next safe point and report the unit as not
// done; rank 0 then hands out nothing more, and every rank exits with 128 + the signal. A rank
// killed outright takes the job down (Open MPI's default); units it left running are run
// again by the next build.
#include "builder/dataset_build.h"

namespace inet {

/// True when this process was started by an MPI launcher (mpirun, srun with PMIx): Open MPI's
/// OMPI_COMM_WORLD_SIZE, or PMIx's PMIX_RANK, is in the environment.
bool launchedByMpi();

/// Runs the build on every rank of MPI_COMM_WORLD (initialises and finalises MPI). On rank 0
/// returns the report of the whole build; on workers, an empty one. `root` is the build folder.
BuildReport buildMpi(const std::filesystem::path& root, const BuildOptions& opt, int* rank,
                     int* ranks);

}  // namespace inet
