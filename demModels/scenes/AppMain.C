#include "AppMain.H"

#include "CommandLine.H"
#include "InputError.H"

#include <iostream>
#include <string>

namespace iceDEM
{

int runApplication(int argc, char** argv, const char* name, const std::function<void(MPI_Comm)>& body)
{
    MPI_Init(&argc, &argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int status = 0;
    try
    {
        body(MPI_COMM_WORLD);
    }
    catch (const HelpRequested& help)
    {
        if (rank == 0)
        {
            std::cout << help.what() << std::endl;
        }
    }
    catch (const InputError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> " << name << " FATAL INPUT ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 1;
    }
    catch (const RunError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> " << name << " FATAL ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 3;
    }
    catch (const std::exception& e)
    {
        std::cerr << "\n--> " << name << " FATAL ERROR (rank " << rank << ")\n    " << e.what() << "\n" << std::endl;
        status = 2;
    }
    if (status == 2)
    {
        MPI_Abort(MPI_COMM_WORLD, status);
    }
    MPI_Finalize();
    return status;
}

} // namespace iceDEM
