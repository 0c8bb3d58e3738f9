// The processes a command runs in: one, or the ranks of an MPI job when cloudvis was started by
// mpirun (docs/data.md). MPI is initialised only when the environment shows an MPI launcher
// started this process (Open MPI's OMPI_COMM_WORLD_SIZE, MPICH's PMI_SIZE or PMI_RANK, PMIx's PMIX_RANK or PMIX_SIZE):
// a plain `cloudvis` never calls MPI_Init, so it starts as fast as before and needs no MPI
// runtime (Open MPI's singleton initialisation would start a helper daemon), and a cloudvis
// under mpirun with one process works as a plain one. Only `generate` to a .pvti runs in
// several processes; every other command refuses to run in more than one (they would write the
// same files from every rank).
#ifndef cloudvis_ProcessGroup_h
#define cloudvis_ProcessGroup_h

#include <vtkSmartPointer.h>

class vtkMPIController;
class vtkMultiProcessController;

namespace cloudvis
{

// The number of processes of the MPI job that started this process, from the launcher's
// environment; 1 when no launcher did.
int LaunchedProcesses();

// While it lives: MPI initialised (when LaunchedProcesses() > 1 or a launcher is present) and a
// controller over the job's processes, else no controller (one process). MPI is finalised when
// it is destroyed, on every path out of the command.
class ProcessGroup
{
public:
  ProcessGroup();
  ~ProcessGroup();
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  // Null for a single process.
  vtkMultiProcessController* Controller() const;
  int Rank() const;
  int Size() const;

private:
  vtkSmartPointer<vtkMPIController> Mpi;
};

} // namespace cloudvis

#endif
