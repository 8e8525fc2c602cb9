// rubbleDEM: builds a rubble beam (scenes.md section 5).
//
// Draws ice blocks, rains them into the water-filled box, settles them to
// rest, freeze-bonds them where they touch and saves the bonded rubble for
// the punch and ridge scenes.
//
// Usage: rubbleDEM [-case DIR] [-stage settle|bond|all] [-shape cuboid|empirical] [-resume]
// Reads  constant/{rubbleProperties,iceProperties,freezeBondProperties,couplingProperties,g},
//        DEM/in.rubbleBeam
// Writes DEM/settled.h5, DEM/rubble.h5 (the bonded rubble),
//        postProcessing/{summary.json,freezeBonds.csv}, VTK/rubble_{particles,bonds}.vtp

#include "AppMain.H"
#include "RubbleScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "rubbleDEM", [&](MPI_Comm comm)
    {
        iceDEM::RubbleScene scene(comm, iceDEM::RubbleSettings::read(argc, argv));
        scene.run();
    });
}
