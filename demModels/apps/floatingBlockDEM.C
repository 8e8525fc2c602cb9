// floatingBlockDEM: a block of bonded ice spheres released onto still water
// settles to floating equilibrium (scenes.md section 9, "Floating block").
//
// Usage: floatingBlockDEM [-case DIR]
// Reads  constant/iceProperties, constant/couplingProperties (waterLevel
//        hydrostatic), constant/g, constant/blockProperties, system/controlDict,
//        DEM/in.floatingBlock
// Writes postProcessing/{draft.csv, summary.json}, VTK/particles.pvd, log lines on stdout.

#include "AppMain.H"
#include "CommandLine.H"
#include "FloatingBlockScene.H"

#include <string>

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "floatingBlockDEM", [&](MPI_Comm comm)
    {
        std::string caseDir = ".";
        iceDEM::CommandLine("floatingBlockDEM")
            .text("-case", "DIR", "the case directory (default .)", caseDir)
            .parse(argc, argv);
        iceDEM::FloatingBlockScene scene(comm, caseDir);
        scene.run();
    });
}
