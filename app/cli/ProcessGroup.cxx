#include "ProcessGroup.h"

#include <vtkMPIController.h>

#include <cstdlib>
#include <string>

namespace cloudvis
{
namespace
{

// The value of the first of these variables that is set to a positive integer, else 0.
int FirstPositive(std::initializer_list<const char*> names)
{
  for (const char* name : names)
  {
    const char* value = std::getenv(name);
    if (value && *value)
    {
      const int parsed = std::atoi(value);
      if (parsed > 0)
      {
        return parsed;
      }
    }
  }
  return 0;
}

bool LaunchedByMpi()
{
  // The variables each launcher sets in the processes it starts.
  for (const char* name :
    { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK", "PMIX_SIZE" })
  {
    if (std::getenv(name))
    {
      return true;
    }
  }
  return false;
}

} // namespace

int LaunchedProcesses()
{
  // The whole job's size (not a node's, as MPI_LOCALNRANKS would be), from each launcher that
  // LaunchedByMpi recognises.
  const int size = FirstPositive({ "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE" });
  return size > 0 ? size : 1;
}

ProcessGroup::ProcessGroup()
{
  if (LaunchedByMpi())
  {
    this->Mpi = vtkSmartPointer<vtkMPIController>::New();
    this->Mpi->Initialize(nullptr, nullptr);
  }
}

ProcessGroup::~ProcessGroup()
{
  if (this->Mpi)
  {
    this->Mpi->Finalize();
  }
}

vtkMultiProcessController* ProcessGroup::Controller() const
{
  return this->Mpi;
}

int ProcessGroup::Rank() const
{
  return this->Mpi ? this->Mpi->GetLocalProcessId() : 0;
}

int ProcessGroup::Size() const
{
  return this->Mpi ? this->Mpi->GetNumberOfProcesses() : 1;
}

} // namespace cloudvis
