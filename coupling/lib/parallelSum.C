#include "parallelSum.H"
#include "Pstream.H"

#include <mpi.h>

namespace Foam
{
namespace iceCoupling
{

// One MPI_Allreduce per coupling step: OpenFOAM's list reductions would
// gather and scatter through the master.
void sumOverRanks(std::vector<double>& values)
{
    if (Pstream::parRun() && !values.empty())
    {
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()),
                      MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    }
}


void minOverRanks(std::vector<int>& values)
{
    if (Pstream::parRun() && !values.empty())
    {
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()),
                      MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    }
}

} // namespace iceCoupling
} // namespace Foam
