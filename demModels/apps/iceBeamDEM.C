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

#include "AppMain.H"
#include "BeamScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "iceBeamDEM", [&](MPI_Comm comm)
    {
        iceDEM::BeamScene scene(comm, iceDEM::BeamSceneOptions::fromArguments(argc, argv));
        scene.run();
    });
}
