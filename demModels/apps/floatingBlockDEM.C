// floatingBlockDEM: a block of bonded ice spheres released onto still water
// settles to floating equilibrium (scenes.md section 9, "Floating block").
//
// Usage: floatingBlockDEM [-case DIR]
// Reads  constant/iceProperties, constant/couplingProperties (waterLevel
//        hydrostatic), constant/g, constant/blockProperties, system/controlDict,
//        DEM/in.floatingBlock
// Writes postProcessing/{draft.csv, summary.json}, VTK/particles.pvd, log lines on stdout.

#include "FloatingBlockScene.H"

#include "InputError.H"

#include <mpi.h>

#include <iostream>
#include <string>

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int status = 0;
    try
    {
        std::string caseDir = ".";
        for (int k = 1; k < argc; ++k)
        {
            const std::string arg = argv[k];
            if (arg == "-case" && k + 1 < argc) caseDir = argv[++k];
            else if (arg == "-help" || arg == "--help")
            {
                if (rank == 0) std::cout << "usage: floatingBlockDEM [-case DIR]" << std::endl;
                MPI_Finalize();
                return 0;
            }
            else throw iceDEM::InputError("command line", arg, "unknown option or missing value; usage: floatingBlockDEM [-case DIR]");
        }
        iceDEM::FloatingBlockScene scene(MPI_COMM_WORLD, caseDir);
        scene.run();
    }
    catch (const iceDEM::InputError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> floatingBlockDEM FATAL INPUT ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 1;
    }
    catch (const iceDEM::RunError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> floatingBlockDEM FATAL ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 3;
    }
    catch (const std::exception& e)
    {
        std::cerr << "\n--> floatingBlockDEM FATAL ERROR (rank " << rank << ")\n    " << e.what() << "\n" << std::endl;
        status = 2;
    }
    if (status == 2)
    {
        MPI_Abort(MPI_COMM_WORLD, status);
    }
    MPI_Finalize();
    return status;
}
