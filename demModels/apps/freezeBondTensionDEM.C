// freezeBondTensionDEM: the virtual freeze-bond tension test (scenes.md section 3).
//
// Two bonded-ice cylinders are pressed together at the confinement pressure,
// freeze-bonded where they touch (strength from the contact force each
// bond carries, constant/freezeBondProperties), unloaded and pulled apart.
//
// Usage: freezeBondTensionDEM [-case DIR] [-pressure PA] [-time MIN] [-label NAME]
//                             [-tensileStrength PA] [-shearStrength PA]
// Reads  constant/{iceProperties,freezeBondProperties,tensionTestProperties},
//        DEM/in.freezeBondTension
// Writes postProcessing/runs/<label>/{summary.json,forceDisplacement.csv,breakage.h5}

#include "AppMain.H"
#include "FreezeBondTensionScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "freezeBondTensionDEM", [&](MPI_Comm comm)
    {
        iceDEM::FreezeBondTensionScene scene(comm, iceDEM::TensionTestSettings::read(argc, argv));
        scene.run();
    });
}
