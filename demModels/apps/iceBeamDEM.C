// iceBeamDEM: the side-loaded level-ice beam (scenes.md section 1).
//
// Builds a dense random packing of the beam with fixed end pads, bonds it,
// pushes a cylindrical platen into its side at mid-span and records the
// platen force, every bond breakage, and ParaView frames, until the load has
// fallen to half its peak (or a maximum travel).
//
// Usage: iceBeamDEM [-case DIR] [-particles N] [-platenSpeed V]
// Reads  constant/iceProperties, constant/beamProperties, system/controlDict,
//        DEM/in.levelIceBeam
// Writes postProcessing/{platenForce.csv, breakage.h5, summary.json},
//        VTK/{particles,bonds}.pvd, log lines on stdout.

#include "BeamScene.H"

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
        iceDEM::BeamSceneOptions options = iceDEM::BeamSceneOptions::fromArguments(argc, argv);
        iceDEM::BeamScene scene(MPI_COMM_WORLD, options);
        scene.run();
    }
    catch (const iceDEM::InputError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> iceBeamDEM FATAL INPUT ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 1;   // every rank reads the same input and stops here alike
    }
    catch (const iceDEM::RunError& e)
    {
        if (rank == 0)
        {
            std::cerr << "\n--> iceBeamDEM FATAL ERROR\n    " << e.what() << "\n" << std::endl;
        }
        status = 3;   // found by every rank together (health checks are collective)
    }
    catch (const std::exception& e)
    {
        std::cerr << "\n--> iceBeamDEM FATAL ERROR (rank " << rank << ")\n    " << e.what() << "\n" << std::endl;
        status = 2;
    }
    if (status == 2)
    {
        MPI_Abort(MPI_COMM_WORLD, status);
    }
    MPI_Finalize();
    return status;
}
