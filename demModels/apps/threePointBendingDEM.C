// threePointBendingDEM: three-point bending of a consolidated-layer ice beam
// (scenes.md section 2).
//
// Builds a dense random packing of the beam at a given particle size, bonds
// it, rests it on two fixed cylinders and pushes a cylindrical platen down at
// mid-span, recording the platen force, the mid-span deflection, the support
// reaction, every bond breakage and ParaView frames, until the load has fallen
// to half its peak (or a maximum travel).
//
// Usage: threePointBendingDEM [-case DIR] [-thickness D] [-quick] [-platenSpeed V] [-steps N] [-resume]
// Reads  constant/iceProperties (constant/iceProperties.quick with -quick),
//        constant/bendingProperties, system/controlDict, DEM/in.threePointBending
// Writes postProcessing/{platenForce.csv, breakage.h5, summary.json},
//        VTK/{particles,bonds}.pvd, log lines on stdout.

#include "AppMain.H"
#include "ThreePointBendingScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "threePointBendingDEM", [&](MPI_Comm comm)
    {
        iceDEM::ThreePointBendingScene scene(comm, iceDEM::ThreePointBendingOptions::fromArguments(argc, argv));
        scene.run();
    });
}
